#pragma once
// The payloads of the protocol's messages. Each struct names its type and
// knows how to write and read itself; read() is bounded (sg::ByteReader)
// and validates every value, so a decoded message is always well formed.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tsr/cluster/frame_header.hpp"
#include "tsr/med/parameters.hpp"
#include "tsr/med/view.hpp"
#include "tsr/sg/byte_reader.hpp"
#include "tsr/sg/byte_writer.hpp"
#include "tsr/sg/types.hpp"

namespace tsr::cluster {

using Nonce = std::array<std::uint8_t, 32>;
using Digest = std::array<std::uint8_t, 32>;  // HMAC-SHA256

// One received message: its type and undecoded payload.
struct Message {
  MessageType type = MessageType::Heartbeat;
  std::vector<std::uint8_t> payload;
};

// Bytes ready for the socket (header + payload); shared so a change list
// encoded once goes to every node.
using Frame = std::shared_ptr<const std::vector<std::uint8_t>>;

// Limits of the decoders beyond the per-type payload maximum.
inline constexpr std::size_t kMaxNameBytes = 256;
inline constexpr std::size_t kMaxReasonBytes = 4096;
inline constexpr std::size_t kMaxBackends = 64;
inline constexpr std::size_t kMaxViewports = 64;
inline constexpr std::size_t kMaxParameters = 256;
inline constexpr std::size_t kMaxJobs = 64;
inline constexpr std::size_t kMaxRectsPerJob = 1 << 14;
inline constexpr std::size_t kMaxOutputs = 32;  // named outputs per job
inline constexpr std::uint32_t kMaxImageSide = 1 << 15;
inline constexpr std::uint64_t kMaxRectPixels = std::uint64_t{1} << 24;  // one tile's result must fit a RenderTile

struct Hello {
  static constexpr MessageType kType = MessageType::Hello;
  std::uint8_t version = kProtocolVersion;
  Nonce clientNonce{};
  std::string clientName;
  void write(sg::ByteWriter& w) const;
  static Hello read(sg::ByteReader& r);
};

struct Challenge {
  static constexpr MessageType kType = MessageType::Challenge;
  Nonce nodeNonce{};
  Digest nodeProof{};  // the node proves it knows the token too
  void write(sg::ByteWriter& w) const;
  static Challenge read(sg::ByteReader& r);
};

struct Auth {
  static constexpr MessageType kType = MessageType::Auth;
  Digest clientProof{};
  void write(sg::ByteWriter& w) const;
  static Auth read(sg::ByteReader& r);
};

struct Welcome {
  static constexpr MessageType kType = MessageType::Welcome;
  std::string nodeName;
  std::uint32_t threads = 0;
  std::vector<std::string> backends;
  void write(sg::ByteWriter& w) const;
  static Welcome read(sg::ByteReader& r);
};

struct Reject {
  static constexpr MessageType kType = MessageType::Reject;
  std::string reason;
  void write(sg::ByteWriter& w) const;
  static Reject read(sg::ByteReader& r);
};

struct Applied {
  static constexpr MessageType kType = MessageType::Applied;
  std::uint64_t version = 0;
  void write(sg::ByteWriter& w) const;
  static Applied read(sg::ByteReader& r);
};

struct ViewportSpec {
  std::uint32_t id = 0;
  std::string backend;
  sg::ContainerId root = sg::kNoContainer;
  sg::ContainerId background = sg::kNoContainer;
  med::Parameters parameters;
  bool operator==(const ViewportSpec&) const = default;
};

// Where a wall node shows its screen (tessera-node --present window).
struct WindowPlacement {
  std::int32_t x = 0, y = 0;            // desktop position of the window
  std::uint32_t width = 0, height = 0;  // 0: the size of the screen's pixels
  bool fullscreen = false;
  bool operator==(const WindowPlacement&) const = default;
};

struct SetViewports {
  static constexpr MessageType kType = MessageType::SetViewports;
  std::vector<ViewportSpec> viewports;         // replaces every viewport the node holds for us
  std::optional<WindowPlacement> window = {};  // a wall screen's window, where the config places it
  void write(sg::ByteWriter& w) const;
  static SetViewports read(sg::ByteReader& r);
};

// Kept: the pixels stay on the node, which presents them itself (a display
// wall that only needs the swap barrier); its tiles carry no pixels.
enum class Compression : std::uint8_t { None = 0, Lz4 = 1, Zstd = 2, Kept = 3 };

struct RenderJob {
  std::uint32_t viewport = 0;
  med::View view;                         // the full image; region unused
  std::vector<med::PixelRect> rects;      // the pixels to render, each a crop of view
  std::vector<std::string> outputs = {};  // named outputs to return with each tile, in this order
  bool resolve = true;                    // false: the client resolves the assembled frame (med::Viewport::resolve)
  bool operator==(const RenderJob&) const = default;
};

struct RenderRequest {
  static constexpr MessageType kType = MessageType::RenderRequest;
  std::uint64_t frame = 0;
  Compression compression = Compression::Lz4;  // what the client prefers for results
  std::vector<RenderJob> jobs;
  // The animation frame shown, for viewports that look ahead (med::Viewport::
  // lookahead, e.g. the path tracer's photons); -1: none.
  std::int64_t sequenceFrame = -1;
  void write(sg::ByteWriter& w) const;
  static RenderRequest read(sg::ByteReader& r);
};

// One rendered rectangle. The pixels (RGBA float, then depth float, then
// RGBA float per named output in `outputs` order, each row by row) follow
// the fields, compressed as `compression` says.
struct RenderTile {
  static constexpr MessageType kType = MessageType::RenderTile;
  std::uint64_t frame = 0;
  std::uint32_t viewport = 0;
  med::PixelRect rect;
  double seconds = 0;
  Compression compression = Compression::None;
  std::vector<std::uint8_t> pixels;
  std::vector<std::string> outputs = {};
  void write(sg::ByteWriter& w) const;
  static RenderTile read(sg::ByteReader& r);
};

struct FrameDone {
  static constexpr MessageType kType = MessageType::FrameDone;
  std::uint64_t frame = 0;
  double busySeconds = 0;
  void write(sg::ByteWriter& w) const;
  static FrameDone read(sg::ByteReader& r);
};

struct Swap {
  static constexpr MessageType kType = MessageType::Swap;
  std::uint64_t frame = 0;
  void write(sg::ByteWriter& w) const;
  static Swap read(sg::ByteReader& r);
};

struct HashQuery {
  static constexpr MessageType kType = MessageType::HashQuery;
  std::uint64_t token = 0;  // echoed, to match replies to queries
  void write(sg::ByteWriter& w) const;
  static HashQuery read(sg::ByteReader& r);
};

struct HashReply {
  static constexpr MessageType kType = MessageType::HashReply;
  std::uint64_t token = 0;
  std::uint64_t version = 0;
  std::uint64_t hash = 0;
  void write(sg::ByteWriter& w) const;
  static HashReply read(sg::ByteReader& r);
};

struct Heartbeat {
  static constexpr MessageType kType = MessageType::Heartbeat;
  std::uint64_t sequence = 0;
  void write(sg::ByteWriter& w) const;
  static Heartbeat read(sg::ByteReader& r);
};

struct HeartbeatAck {
  static constexpr MessageType kType = MessageType::HeartbeatAck;
  std::uint64_t sequence = 0;
  void write(sg::ByteWriter& w) const;
  static HeartbeatAck read(sg::ByteReader& r);
};

struct ErrorReport {
  static constexpr MessageType kType = MessageType::Error;
  std::string reason;
  void write(sg::ByteWriter& w) const;
  static ErrorReport read(sg::ByteReader& r);
};

struct Bye {
  static constexpr MessageType kType = MessageType::Bye;
  void write(sg::ByteWriter&) const {}
  static Bye read(sg::ByteReader&) { return {}; }
};

// Frame `frame` of an animation, posed ahead of the one shown: `changes`
// (an encoded change list, a snapshot or the delta from the one before)
// brings the node's second replica, the scene ahead, to it, and viewports
// that look ahead prepare it (med::Viewport::prepare).
struct Prepare {
  static constexpr MessageType kType = MessageType::Prepare;
  std::int64_t frame = 0;
  std::vector<std::uint8_t> changes;
  void write(sg::ByteWriter& w) const;
  static Prepare read(sg::ByteReader& r);
};

// Header + payload of a message struct.
Frame frameFromPayload(MessageType type, std::span<const std::uint8_t> payload);
template <class T>
Frame makeFrame(const T& message) {
  std::vector<std::uint8_t> payload;
  sg::ByteWriter w(payload);
  message.write(w);
  return frameFromPayload(T::kType, payload);
}

// Decodes a received message as T; throws ProtocolError (Unexpected for
// another type, Malformed with the byte offset for bad payloads).
void checkDecodable(MessageType expected, const Message& message);
[[noreturn]] void rethrowAsMalformed(MessageType type);
template <class T>
T parse(const Message& message) {
  checkDecodable(T::kType, message);
  try {
    sg::ByteReader r(message.payload);
    T decoded = T::read(r);
    if (!r.atEnd()) r.fail("trailing bytes after the message");
    return decoded;
  } catch (...) {
    rethrowAsMalformed(T::kType);
  }
}

}  // namespace tsr::cluster
