#pragma once
// The whole node protocol: one enum, one handler per message (see
// node_session.cpp and node_link.cpp). Bulk data (change lists, pixels)
// is the payload of Snapshot, Changes and RenderTile.
//
//   client -> node              node -> client
//   Hello                       Challenge        handshake (auth.hpp)
//   Auth                        Welcome | Reject
//   Snapshot | Changes          Applied          replica follows the client
//   SetViewports                Error            viewports by back-end name
//   RenderRequest               RenderTile*, FrameDone
//   Swap                                         wall barrier release
//   HashQuery                   HashReply        replica check
//   Heartbeat                   HeartbeatAck     liveness
//   Bye                                          orderly close
//   Prepare                                      a frame ahead, for temporal viewports
#include <cstddef>
#include <cstdint>

namespace tsr::cluster {

enum class MessageType : std::uint8_t {
  Hello = 1,
  Challenge,
  Auth,
  Welcome,
  Reject,
  Snapshot,
  Changes,
  Applied,
  SetViewports,
  RenderRequest,
  RenderTile,
  FrameDone,
  Swap,
  HashQuery,
  HashReply,
  Heartbeat,
  HeartbeatAck,
  Error,
  Bye,
  Prepare,
};

enum class Sender : std::uint8_t { Client, Node };

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
