#include "tsr/cluster/node_address.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>

namespace tsr::cluster {

NodeAddress parseNodeAddress(const std::string& text) {
  auto colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0)
    throw std::invalid_argument("node address '" + text + "' is not HOST:PORT");
  NodeAddress a;
  a.host = text.substr(0, colon);
  if (a.host.size() > 2 && a.host.front() == '[' && a.host.back() == ']') a.host = a.host.substr(1, a.host.size() - 2);
  // A host name or an IP address, nothing else: addresses travel on to
  // other programs' command lines (tessera-launch's --nodes A,B), where a
  // comma or a space would split one address into two.
  if (a.host.size() > 255 || !std::all_of(a.host.begin(), a.host.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_' || c == ':' || c == '%';
      }))
    throw std::invalid_argument("node address '" + text.substr(0, 64) +
                                "': the host must be a name or an IP address (letters, digits, '.', '-', '_', ':')");
  std::string port = text.substr(colon + 1);
  unsigned value = 0;
  auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
  if (port.empty() || ec != std::errc() || end != port.data() + port.size() || value > 65535)
    throw std::invalid_argument("node address '" + text + "': port must be 0..65535");
  a.port = static_cast<std::uint16_t>(value);
  return a;
}

std::vector<NodeAddress> parseNodeList(const std::string& text) {
  std::vector<NodeAddress> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    auto comma = text.find(',', start);
    std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (!item.empty()) out.push_back(parseNodeAddress(item));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (out.empty()) throw std::invalid_argument("empty node list");
  return out;
}

}  // namespace tsr::cluster
