#pragma once
// HOST:PORT as given on command lines and in configs.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace tsr::cluster {

struct NodeAddress {
  std::string host = "127.0.0.1";
  std::uint16_t port = 0;
  std::string text() const { return host + ":" + std::to_string(port); }
  bool operator==(const NodeAddress&) const = default;
};

// Throws std::invalid_argument for a missing host, one with other characters
// than a host name or IP address has, or a port outside 0..65535.
NodeAddress parseNodeAddress(const std::string& text);
// "a:1,b:2" -> two addresses.
std::vector<NodeAddress> parseNodeList(const std::string& text);

}  // namespace tsr::cluster
