#include <cstdlib>
#include <string>

#include "fuzz_targets.hpp"
#include "launch_rank.hpp"
#include "rendezvous_text.hpp"

namespace tsr::fuzz {

// What an accepted address comes back as when a node rank writes it out
// again (publish() writes text() and a newline; the socket sends "rank R
// text()"): a round trip that changed it would hand the client another node.
void launchAddressFile(Bytes bytes) {
  const std::string text(bytes.begin(), bytes.end());
  cluster::NodeAddress address;
  try {
    address = app::parseAddressFile(text, "fuzz-input");
  } catch (const app::LaunchError&) {
    return;
  }
  if (app::parseAddressFile(address.text() + "\n", "again") != address) std::abort();
}

// The bytes a node rank's connection delivers, up to the first newline as
// SocketRendezvous::gather cuts them, for the largest job.
void launchRankLine(Bytes bytes) {
  const std::string buffer(bytes.begin(), bytes.end());
  const auto line = app::parseRankLine(buffer.substr(0, buffer.find('\n')), app::kMaxJobSize);
  if (!line) return;
  if (line->rank == 0 || line->rank >= app::kMaxJobSize || line->address.port == 0) std::abort();
  const auto again =
      app::parseRankLine("rank " + std::to_string(line->rank) + " " + line->address.text(), app::kMaxJobSize);
  if (!again || again->rank != line->rank || again->address != line->address) std::abort();
}

}  // namespace tsr::fuzz
