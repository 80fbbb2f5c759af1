#include "tsr/cluster/message_type.hpp"

#include <array>
#include <stdexcept>

#include "tsr/cluster/messages.hpp"

namespace tsr::cluster {

namespace {
// Generated from the one list of message types: the spec of each type byte.
template <class... M>
constexpr std::array<const MessageSpec*, 256> specTable(MessageList<M...>) {
  std::array<const MessageSpec*, 256> table{};
  auto add = [&](const MessageSpec& s) {
    auto& slot = table[static_cast<std::uint8_t>(s.type)];
    if (slot || s.type == MessageType{}) throw std::logic_error("message type numbers must be unique and not 0");
    slot = &s;
  };
  (add(M::kSpec), ...);
  return table;
}
constexpr std::array<const MessageSpec*, 256> kSpecs = specTable(Messages{});  // a clash fails to compile
}  // namespace

const MessageSpec* findSpec(std::uint8_t type) { return kSpecs[type]; }

const MessageSpec& spec(MessageType type) {
  if (const MessageSpec* s = findSpec(static_cast<std::uint8_t>(type))) return *s;
  throw std::logic_error("message type without a spec");
}

const char* name(MessageType type) {
  const MessageSpec* s = findSpec(static_cast<std::uint8_t>(type));
  return s ? s->name : "unknown";
}

}  // namespace tsr::cluster
