#pragma once
// The protocol's messages, each said once: its struct declares its type
// number, name, sender, largest payload and whether it may come during the
// handshake (kType, kSpec), and its fields with their codecs and bounds
// (fields(), see message_fields.hpp). Writing, reading, the frame header's
// lookup by type byte and the codec tests are generated from that and from
// the one list of message types at the end (`Messages`).
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
//
// Adding a message: declare it here and add it to `Messages`; handle it on
// the receiving side (NodeSession::on<M> in src/node/node_session.cpp, or
// ClusterWindow::Impl::receive() in src/client/node_messages.cpp) and send it
// from the other.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "tsr/cluster/field_codecs.hpp"
#include "tsr/cluster/frame_header.hpp"
#include "tsr/cluster/message_fields.hpp"
#include "tsr/med/parameters.hpp"
#include "tsr/med/view.hpp"
#include "tsr/sg/changes/change_list.hpp"
#include "tsr/sg/types.hpp"
#include "tsr/sg/wire/byte_reader.hpp"
#include "tsr/sg/wire/byte_writer.hpp"

namespace tsr::cluster {

using Nonce = std::array<std::uint8_t, 32>;
using Digest = std::array<std::uint8_t, 32>;  // HMAC-SHA256

// One received message: its type and undecoded payload.
struct Message {
  MessageType type{};
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
inline constexpr std::uint32_t kMaxViewportId = kMaxViewports * 1024;
inline constexpr std::size_t kMaxParameters = 256;
inline constexpr std::size_t kMaxJobs = 64;
inline constexpr std::size_t kMaxRectsPerJob = 1 << 14;
inline constexpr std::size_t kMaxOutputs = 32;  // named outputs per job
inline constexpr std::uint32_t kMaxImageSide = 1 << 15;
inline constexpr std::uint64_t kMaxRectPixels = std::uint64_t{1} << 24;  // one tile's result must fit a RenderTile
inline constexpr std::uint32_t kMaxThreads = 1 << 16;
// What a tile reports of its work (RenderTile): samples per pixel it holds,
// as far as any back-end's spp parameter goes, and rays cast, kept within
// what a JSON number carries exactly.
inline constexpr std::uint32_t kMaxTileSamples = 1 << 24;
inline constexpr std::uint64_t kMaxTileRays = std::uint64_t{1} << 53;
// An animation frame number: far beyond any sequence a person renders, yet
// well inside std::int64_t.
inline constexpr std::uint64_t kMaxSequenceFrame = std::uint64_t{1} << 40;

// Bulk messages are bounded by what a sane scene or image needs; control
// messages by a little more than their largest valid encoding.
inline constexpr bool kBeforeAuth = true, kAfterAuth = false;

struct Hello {
  static constexpr MessageType kType{1};
  static constexpr MessageSpec kSpec{kType, "Hello", Sender::Client, 512, kBeforeAuth};
  std::uint8_t version = kProtocolVersion;
  Nonce clientNonce{};
  std::string clientName;
  static constexpr auto fields() {
    return std::tuple{field("version", &Hello::version, wire::byte()),
                      field("client nonce", &Hello::clientNonce, wire::fixedBytes()),
                      field("client name", &Hello::clientName, wire::text(kMaxNameBytes))};
  }
  bool operator==(const Hello&) const = default;
};

struct Challenge {
  static constexpr MessageType kType{2};
  static constexpr MessageSpec kSpec{kType, "Challenge", Sender::Node, 128, kBeforeAuth};
  Nonce nodeNonce{};
  Digest nodeProof{};  // the node proves it knows the token too
  static constexpr auto fields() {
    return std::tuple{field("node nonce", &Challenge::nodeNonce, wire::fixedBytes()),
                      field("node proof", &Challenge::nodeProof, wire::fixedBytes())};
  }
  bool operator==(const Challenge&) const = default;
};

struct Auth {
  static constexpr MessageType kType{3};
  static constexpr MessageSpec kSpec{kType, "Auth", Sender::Client, 64, kBeforeAuth};
  Digest clientProof{};
  static constexpr auto fields() { return std::tuple{field("client proof", &Auth::clientProof, wire::fixedBytes())}; }
  bool operator==(const Auth&) const = default;
};

struct Welcome {
  static constexpr MessageType kType{4};
  static constexpr MessageSpec kSpec{kType, "Welcome", Sender::Node, 64 * kKiB, kBeforeAuth};
  std::string nodeName;
  std::uint32_t threads = 0;
  std::vector<std::string> backends;
  static constexpr auto fields() {
    return std::tuple{field("node name", &Welcome::nodeName, wire::text(kMaxNameBytes)),
                      field("thread count", &Welcome::threads, wire::varint(kMaxThreads)),
                      field("back-end", &Welcome::backends, wire::listOf(kMaxBackends, 1, wire::text(kMaxNameBytes)))};
  }
  bool operator==(const Welcome&) const = default;
};

struct Reject {
  static constexpr MessageType kType{5};
  static constexpr MessageSpec kSpec{kType, "Reject", Sender::Node, 8 * kKiB, kBeforeAuth};
  std::string reason;
  static constexpr auto fields() { return std::tuple{field("reason", &Reject::reason, wire::text(kMaxReasonBytes))}; }
  bool operator==(const Reject&) const = default;
};

// The whole scene as one change list (sg::encode), for a node that joins or
// starts over; decoded by sg::decode, which bounds it.
struct Snapshot {
  static constexpr MessageType kType{6};
  static constexpr MessageSpec kSpec{kType, "Snapshot", Sender::Client, 1024 * kMiB, kAfterAuth};
  std::vector<std::uint8_t> changes;
  static constexpr auto fields() {
    return std::tuple{field("change list", &Snapshot::changes, wire::rest<Snapshot>())};
  }
  bool operator==(const Snapshot&) const = default;
};

// One frame's change list (sg::encode), from the version the node holds.
struct Changes {
  static constexpr MessageType kType{7};
  static constexpr MessageSpec kSpec{kType, "Changes", Sender::Client, 1024 * kMiB, kAfterAuth};
  std::vector<std::uint8_t> changes;
  static constexpr auto fields() { return std::tuple{field("change list", &Changes::changes, wire::rest<Changes>())}; }
  bool operator==(const Changes&) const = default;
};

struct Applied {
  static constexpr MessageType kType{8};
  static constexpr MessageSpec kSpec{kType, "Applied", Sender::Node, 32, kAfterAuth};
  std::uint64_t version = 0;
  static constexpr auto fields() { return std::tuple{field("version", &Applied::version, wire::varint())}; }
  bool operator==(const Applied&) const = default;
};

struct ViewportSpec {
  std::uint32_t id = 0;
  std::string backend;
  sg::ContainerId root = sg::kNoContainer;
  sg::ContainerId background = sg::kNoContainer;
  med::Parameters parameters;
  static constexpr auto fields() {
    return std::tuple{field("viewport id", &ViewportSpec::id, wire::varint(kMaxViewportId)),
                      field("back-end name", &ViewportSpec::backend, wire::nonEmptyText(kMaxNameBytes)),
                      field("root", &ViewportSpec::root, wire::varint()),
                      field("background", &ViewportSpec::background, wire::varint()),
                      field("parameters", &ViewportSpec::parameters,
                            wire::parameters(kMaxParameters, kMaxNameBytes, kMaxReasonBytes))};
  }
  bool operator==(const ViewportSpec&) const = default;
};

// Where a wall node shows its screen (tessera-node --present window).
struct WindowPlacement {
  std::int32_t x = 0, y = 0;            // desktop position of the window
  std::uint32_t width = 0, height = 0;  // 0: the size of the screen's pixels
  bool fullscreen = false;
  static constexpr std::int64_t kMaxPosition = kMaxImageSide;
  static constexpr auto fields() {
    return std::tuple{field("window x", &WindowPlacement::x, wire::svarint(-kMaxPosition, kMaxPosition)),
                      field("window y", &WindowPlacement::y, wire::svarint(-kMaxPosition, kMaxPosition)),
                      field("window width", &WindowPlacement::width, wire::varint(kMaxImageSide)),
                      field("window height", &WindowPlacement::height, wire::varint(kMaxImageSide)),
                      field("fullscreen flag", &WindowPlacement::fullscreen, wire::flag())};
  }
  bool operator==(const WindowPlacement&) const = default;
};

struct SetViewports {
  static constexpr MessageType kType{9};
  static constexpr MessageSpec kSpec{kType, "SetViewports", Sender::Client, 1 * kMiB, kAfterAuth};
  std::vector<ViewportSpec> viewports;         // replaces every viewport the node holds for us
  std::optional<WindowPlacement> window = {};  // a wall screen's window, where the config places it
  static constexpr auto fields() {
    return std::tuple{field("viewport", &SetViewports::viewports,
                            wire::listOf(kMaxViewports, 5, wire::nested(), &ViewportSpec::id, "viewport id")),
                      field("window", &SetViewports::window, wire::optionalOf(wire::nested()))};
  }
  bool operator==(const SetViewports&) const = default;
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
  static constexpr auto fields() {
    return std::tuple{
        field("viewport id", &RenderJob::viewport, wire::varint(kMaxViewportId)),
        field("view", &RenderJob::view, wire::view(kMaxImageSide, kMaxRectPixels)),
        field("rectangle", &RenderJob::rects,
              wire::listOf(kMaxRectsPerJob, 4, wire::rectIn(&RenderJob::view, kMaxImageSide, kMaxRectPixels))),
        // Distinct, non-empty names: each is one image in the tile's pixels.
        field("output name", &RenderJob::outputs,
              wire::distinctListOf(kMaxOutputs, 2, wire::nonEmptyText(kMaxNameBytes))),
        field("resolve flag", &RenderJob::resolve, wire::flag())};
  }
  bool operator==(const RenderJob&) const = default;
};

struct RenderRequest {
  static constexpr MessageType kType{10};
  static constexpr MessageSpec kSpec{kType, "RenderRequest", Sender::Client, 4 * kMiB, kAfterAuth};
  std::uint64_t frame = 0;
  Compression compression = Compression::Lz4;  // what the client prefers for results
  std::vector<RenderJob> jobs;
  // The animation frame shown, for viewports that look ahead (med::Viewport::
  // lookahead, e.g. the path tracer's photons); -1: none.
  std::int64_t sequenceFrame = -1;
  static constexpr auto fields() {
    return std::tuple{
        field("frame", &RenderRequest::frame, wire::varint()),
        field("compression", &RenderRequest::compression, wire::enumUpTo(Compression::Kept)),
        field("render job", &RenderRequest::jobs, wire::listOf(kMaxJobs, 100, wire::nested())),
        field("animation frame", &RenderRequest::sequenceFrame, wire::animationFrame(-1, kMaxSequenceFrame))};
  }
  bool operator==(const RenderRequest&) const = default;
};

// One rendered rectangle. The pixels (RGBA float, then depth float, then
// RGBA float per named output in `outputs` order, each row by row) follow
// the fields, compressed as `compression` says; decodePixels checks them.
// `seconds`, `syncSeconds`, `samples` and `rays` say what rendering it cost
// (the client's workload figures): `syncSeconds` is the part of `seconds`
// spent catching the back-end up with the replica (med::RenderStats::
// syncSeconds: the frame's scene changes land on the first tile a node
// renders), `samples` the samples per pixel the tile holds after this render
// (med::RenderStats::samples; 0 for a back-end without), `rays` those cast
// by this render.
struct RenderTile {
  static constexpr MessageType kType{11};
  static constexpr MessageSpec kSpec{kType, "RenderTile", Sender::Node, 1024 * kMiB, kAfterAuth};
  std::uint64_t frame = 0;
  std::uint32_t viewport = 0;
  med::PixelRect rect;
  double seconds = 0;
  Compression compression = Compression::None;
  std::vector<std::uint8_t> pixels;
  std::vector<std::string> outputs = {};
  std::uint32_t samples = 0;
  std::uint64_t rays = 0;
  double syncSeconds = 0;
  static constexpr bool keptOnNode(const RenderTile& t) { return t.compression == Compression::Kept; }
  static constexpr auto fields() {
    return std::tuple{
        field("frame", &RenderTile::frame, wire::varint()),
        field("viewport id", &RenderTile::viewport, wire::varint(kMaxViewportId)),
        field("rectangle", &RenderTile::rect, wire::rect(kMaxImageSide, kMaxRectPixels)),
        field("seconds", &RenderTile::seconds, wire::seconds()),
        field("sync seconds", &RenderTile::syncSeconds, wire::seconds()),
        field("samples per pixel", &RenderTile::samples, wire::varint(kMaxTileSamples)),
        field("ray count", &RenderTile::rays, wire::varint(kMaxTileRays)),
        field("output name", &RenderTile::outputs,
              wire::distinctListOf(kMaxOutputs, 2, wire::nonEmptyText(kMaxNameBytes))),
        field("compression", &RenderTile::compression, wire::enumUpTo(Compression::Kept)),
        field("pixels", &RenderTile::pixels,
              wire::restEmptyWhen(&RenderTile::keptOnNode, "pixels kept on the node, yet the tile carries bytes"))};
  }
  bool operator==(const RenderTile&) const = default;
};

struct FrameDone {
  static constexpr MessageType kType{12};
  static constexpr MessageSpec kSpec{kType, "FrameDone", Sender::Node, 64, kAfterAuth};
  std::uint64_t frame = 0;
  double busySeconds = 0;
  static constexpr auto fields() {
    return std::tuple{field("frame", &FrameDone::frame, wire::varint()),
                      field("busy seconds", &FrameDone::busySeconds, wire::seconds())};
  }
  bool operator==(const FrameDone&) const = default;
};

struct Swap {
  static constexpr MessageType kType{13};
  static constexpr MessageSpec kSpec{kType, "Swap", Sender::Client, 32, kAfterAuth};
  std::uint64_t frame = 0;
  static constexpr auto fields() { return std::tuple{field("frame", &Swap::frame, wire::varint())}; }
  bool operator==(const Swap&) const = default;
};

struct HashQuery {
  static constexpr MessageType kType{14};
  static constexpr MessageSpec kSpec{kType, "HashQuery", Sender::Client, 32, kAfterAuth};
  std::uint64_t token = 0;  // echoed, to match replies to queries
  static constexpr auto fields() { return std::tuple{field("token", &HashQuery::token, wire::varint())}; }
  bool operator==(const HashQuery&) const = default;
};

struct HashReply {
  static constexpr MessageType kType{15};
  static constexpr MessageSpec kSpec{kType, "HashReply", Sender::Node, 64, kAfterAuth};
  std::uint64_t token = 0;
  std::uint64_t version = 0;
  std::uint64_t hash = 0;
  static constexpr auto fields() {
    return std::tuple{field("token", &HashReply::token, wire::varint()),
                      field("version", &HashReply::version, wire::varint()),
                      field("content hash", &HashReply::hash, wire::fixedBytes())};
  }
  bool operator==(const HashReply&) const = default;
};

struct Heartbeat {
  static constexpr MessageType kType{16};
  static constexpr MessageSpec kSpec{kType, "Heartbeat", Sender::Client, 32, kAfterAuth};
  std::uint64_t sequence = 0;
  static constexpr auto fields() { return std::tuple{field("sequence", &Heartbeat::sequence, wire::varint())}; }
  bool operator==(const Heartbeat&) const = default;
};

struct HeartbeatAck {
  static constexpr MessageType kType{17};
  static constexpr MessageSpec kSpec{kType, "HeartbeatAck", Sender::Node, 32, kAfterAuth};
  std::uint64_t sequence = 0;
  static constexpr auto fields() { return std::tuple{field("sequence", &HeartbeatAck::sequence, wire::varint())}; }
  bool operator==(const HeartbeatAck&) const = default;
};

// What went wrong on the node, typed so the client decides by `kind`; the
// reason is for people.
struct ErrorReport {
  static constexpr MessageType kType{18};
  static constexpr MessageSpec kSpec{kType, "Error", Sender::Node, 8 * kKiB, kAfterAuth};
  enum class Kind : std::uint8_t {
    ProtocolViolation = 0,  // the client broke the protocol (a malformed or unexpected message); the node hangs up
    SceneRejected = 1,      // a change list, shown or ahead, does not decode or apply; the node hangs up
    UnknownBackend = 2,     // a viewport names a back-end this node lacks: said when the viewports arrive (the
                            // session goes on) and when a render or prepare needs it (the node hangs up)
    InvalidParameter = 3,   // a viewport's parameters are refused (med::ParameterError from creating or
                            // rendering it); the node hangs up
    RenderFailed = 4,       // rendering a request failed otherwise; the node hangs up
    PrepareFailed = 5,      // preparing a frame ahead failed otherwise; the node hangs up
  };
  Kind kind = Kind::RenderFailed;
  std::string reason;
  static constexpr auto fields() {
    return std::tuple{field("error kind", &ErrorReport::kind, wire::enumUpTo(Kind::PrepareFailed)),
                      field("reason", &ErrorReport::reason, wire::text(kMaxReasonBytes))};
  }
  bool operator==(const ErrorReport&) const = default;
};
const char* name(ErrorReport::Kind kind);

struct Bye {
  static constexpr MessageType kType{19};
  static constexpr MessageSpec kSpec{kType, "Bye", Sender::Client, 0, kAfterAuth};
  static constexpr auto fields() { return std::tuple{}; }
  bool operator==(const Bye&) const = default;
};

// Frame `frame` of an animation, posed ahead of the one shown: `changes`
// (an encoded change list, a snapshot or the delta from the one before)
// brings the node's second replica, the scene ahead, to it, and viewports
// that look ahead prepare it (med::Viewport::prepare).
struct Prepare {
  static constexpr MessageType kType{20};
  static constexpr MessageSpec kSpec{kType, "Prepare", Sender::Client, 1024 * kMiB, kAfterAuth};
  std::int64_t frame = 0;
  std::vector<std::uint8_t> changes;  // decoded by sg::decode, bounded as Changes are
  static constexpr auto fields() {
    return std::tuple{field("animation frame", &Prepare::frame, wire::animationFrame(0, kMaxSequenceFrame)),
                      field("change list", &Prepare::changes, wire::rest<Prepare>())};
  }
  bool operator==(const Prepare&) const = default;
};

// The one list of message types: the frame header's lookup, the receivers'
// dispatch and the codec tests are generated from it.
template <class... M>
struct MessageList {
  // Calls fn.template operator()<M>() for each message type, in order.
  template <class Fn>
  static void forEach(Fn&& fn) {
    (fn.template operator()<M>(), ...);
  }
  // Calls fn.template operator()<M>() for the message of `type`; false when none is.
  template <class Fn>
  static bool visit(MessageType type, Fn&& fn) {
    return ((type == M::kType ? (fn.template operator()<M>(), true) : false) || ...);
  }
  static constexpr std::size_t size = sizeof...(M);
};

using Messages =
    MessageList<Hello, Challenge, Auth, Welcome, Reject, Snapshot, Changes, Applied, SetViewports, RenderRequest,
                RenderTile, FrameDone, Swap, HashQuery, HashReply, Heartbeat, HeartbeatAck, ErrorReport, Bye, Prepare>;

// Header + payload of a message struct.
Frame frameFromPayload(MessageType type, std::span<const std::uint8_t> payload);
// A Snapshot or Changes message, the list encoded straight into the frame
// (no second copy of a scene's bytes).
Frame changeListFrame(MessageType type, const sg::ChangeList& list);
template <class T>
Frame makeFrame(const T& message) {
  std::vector<std::uint8_t> payload;
  sg::ByteWriter w(payload);
  writeFields(w, message);
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
    T decoded{};
    readFields(r, decoded);
    if (!r.atEnd()) r.fail("trailing bytes after the message");
    return decoded;
  } catch (...) {
    rethrowAsMalformed(T::kType);
  }
}

}  // namespace tsr::cluster
