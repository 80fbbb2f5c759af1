#include "tsr/cluster/message_type.hpp"

#include <stdexcept>

namespace tsr::cluster {

namespace {
constexpr std::size_t KiB = 1024, MiB = 1024 * KiB;

// Bulk messages are bounded by what a sane scene or image needs; control
// messages by a little more than their largest valid encoding.
constexpr MessageSpec kSpecs[] = {
    {MessageType::Hello, "Hello", Sender::Client, 512, true},
    {MessageType::Challenge, "Challenge", Sender::Node, 128, true},
    {MessageType::Auth, "Auth", Sender::Client, 64, true},
    {MessageType::Welcome, "Welcome", Sender::Node, 64 * KiB, true},
    {MessageType::Reject, "Reject", Sender::Node, 8 * KiB, true},
    {MessageType::Snapshot, "Snapshot", Sender::Client, 1024 * MiB, false},
    {MessageType::Changes, "Changes", Sender::Client, 1024 * MiB, false},
    {MessageType::Applied, "Applied", Sender::Node, 32, false},
    {MessageType::SetViewports, "SetViewports", Sender::Client, 1 * MiB, false},
    {MessageType::RenderRequest, "RenderRequest", Sender::Client, 4 * MiB, false},
    {MessageType::RenderTile, "RenderTile", Sender::Node, 1024 * MiB, false},
    {MessageType::FrameDone, "FrameDone", Sender::Node, 64, false},
    {MessageType::Swap, "Swap", Sender::Client, 32, false},
    {MessageType::HashQuery, "HashQuery", Sender::Client, 32, false},
    {MessageType::HashReply, "HashReply", Sender::Node, 64, false},
    {MessageType::Heartbeat, "Heartbeat", Sender::Client, 32, false},
    {MessageType::HeartbeatAck, "HeartbeatAck", Sender::Node, 32, false},
    {MessageType::Error, "Error", Sender::Node, 8 * KiB, false},
    {MessageType::Bye, "Bye", Sender::Client, 0, false},
    {MessageType::Prepare, "Prepare", Sender::Client, 1024 * MiB, false},
};
}  // namespace

const MessageSpec* findSpec(std::uint8_t type) {
  for (const auto& s : kSpecs)
    if (static_cast<std::uint8_t>(s.type) == type) return &s;
  return nullptr;
}

const MessageSpec& spec(MessageType type) {
  if (const MessageSpec* s = findSpec(static_cast<std::uint8_t>(type))) return *s;
  throw std::logic_error("message type without a spec");
}

const char* name(MessageType type) {
  const MessageSpec* s = findSpec(static_cast<std::uint8_t>(type));
  return s ? s->name : "unknown";
}

}  // namespace tsr::cluster
