#pragma once
// What the node ranks tell rank 0, as text from outside the process: the
// contents of an address file (DirectoryRendezvous) and the line a node rank
// sends over its connection (SocketRendezvous). Both bounded and checked
// here, apart from the folders and sockets they arrive through.
#include <cstddef>
#include <optional>
#include <string>

#include "tsr/cluster/node_address.hpp"

namespace tsr::app {

// Address files and rank lines longer than this are refused. What a node
// rank writes always fits: "rank 4095 " + a host of at most 255 characters
// + ":65535\n" (the fuzz target found a 256-byte limit that refused some).
inline constexpr std::size_t kMaxRendezvousText = 512;

// One "HOST:PORT" line (a trailing newline and nothing else after it); port
// 0 is refused. Throws LaunchError naming `file`.
cluster::NodeAddress parseAddressFile(const std::string& text, const std::string& file);

struct RankLine {
  unsigned rank = 0;
  cluster::NodeAddress address;
};
// "rank R HOST:PORT" with R in 1..size-1 and a port other than 0 (without
// its newline); nothing for anything else.
std::optional<RankLine> parseRankLine(const std::string& line, unsigned size);

}  // namespace tsr::app
