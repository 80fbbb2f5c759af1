#include "rendezvous_text.hpp"

#include <charconv>
#include <sstream>

#include "launch_rank.hpp"

namespace tsr::app {

cluster::NodeAddress parseAddressFile(const std::string& text, const std::string& file) {
  if (text.size() > kMaxRendezvousText)
    throw LaunchError("rendezvous file " + file + " holds " + std::to_string(text.size()) +
                      " bytes, not one HOST:PORT line");
  const auto newline = text.find('\n');
  const std::string line = text.substr(0, newline);
  if (newline != std::string::npos && newline + 1 != text.size())
    throw LaunchError("rendezvous file " + file + " holds more than one line");
  cluster::NodeAddress address;
  try {
    address = cluster::parseNodeAddress(line);
  } catch (const std::exception& e) {
    throw LaunchError("rendezvous file " + file + " does not hold HOST:PORT: " + e.what());
  }
  if (address.port == 0) throw LaunchError("rendezvous file " + file + " gives port 0");
  return address;
}

std::optional<RankLine> parseRankLine(const std::string& line, unsigned size) {
  if (line.size() > kMaxRendezvousText) return std::nullopt;
  std::istringstream words(line);
  std::string word, rankText, addressText, extra;
  if (!(words >> word >> rankText >> addressText) || word != "rank" || (words >> extra)) return std::nullopt;
  RankLine out;
  auto [end, ec] = std::from_chars(rankText.data(), rankText.data() + rankText.size(), out.rank);
  if (ec != std::errc() || end != rankText.data() + rankText.size() || out.rank == 0 || out.rank >= size)
    return std::nullopt;
  try {
    out.address = cluster::parseNodeAddress(addressText);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (out.address.port == 0) return std::nullopt;
  return out;
}

}  // namespace tsr::app
