#pragma once
// What the frame header needs to know about a message type: its number,
// name, which side sends it, its largest payload and whether it may arrive
// during the handshake. Each message declares these with its struct
// (messages.hpp, `kType` and `kSpec`); findSpec is generated from the one
// list of message types there (`Messages`).
#include <cstddef>
#include <cstdint>

namespace tsr::cluster {

// A message's type byte; the numbers are declared by the messages
// themselves (`static constexpr MessageType kType{N}`). 0 names none.
enum class MessageType : std::uint8_t {};

enum class Sender : std::uint8_t { Client, Node };

inline constexpr std::size_t kKiB = 1024, kMiB = 1024 * kKiB;

struct MessageSpec {
  MessageType type;
  const char* name;
  Sender sender;
  std::size_t maxPayload;  // a header announcing more is a protocol violation
  bool beforeAuth;         // allowed while the handshake is running
};

// Null for a byte that names no message.
const MessageSpec* findSpec(std::uint8_t type);
const MessageSpec& spec(MessageType type);
const char* name(MessageType type);

}  // namespace tsr::cluster
