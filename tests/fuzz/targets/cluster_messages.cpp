#include "fuzz_targets.hpp"
#include "tsr/cluster/frame_header.hpp"
#include "tsr/cluster/messages.hpp"
#include "tsr/cluster/pixel_codec.hpp"
#include "tsr/cluster/protocol_error.hpp"
#include "tsr/sg/errors.hpp"
#include "tsr/sg/wire_codec.hpp"

namespace tsr::cluster {
namespace {

// What a node or client does with a payload of this type: parse it, and
// for bulk data decode what it carries.
void decodePayload(const Message& m) {
  switch (m.type) {
    case MessageType::Hello:
      parse<Hello>(m);
      return;
    case MessageType::Challenge:
      parse<Challenge>(m);
      return;
    case MessageType::Auth:
      parse<Auth>(m);
      return;
    case MessageType::Welcome:
      parse<Welcome>(m);
      return;
    case MessageType::Reject:
      parse<Reject>(m);
      return;
    case MessageType::Snapshot:
    case MessageType::Changes: {
      sg::DecodeLimits limits;
      limits.maxArrayElements = 1 << 20;
      sg::decode(m.payload, limits);
      return;
    }
    case MessageType::Applied:
      parse<Applied>(m);
      return;
    case MessageType::SetViewports:
      parse<SetViewports>(m);
      return;
    case MessageType::RenderRequest:
      parse<RenderRequest>(m);
      return;
    case MessageType::RenderTile: {
      const RenderTile tile = parse<RenderTile>(m);
      decodePixels(tile.rect.width(), tile.rect.height(), tile.compression, tile.pixels, tile.outputs);
      return;
    }
    case MessageType::FrameDone:
      parse<FrameDone>(m);
      return;
    case MessageType::Swap:
      parse<Swap>(m);
      return;
    case MessageType::HashQuery:
      parse<HashQuery>(m);
      return;
    case MessageType::HashReply:
      parse<HashReply>(m);
      return;
    case MessageType::Heartbeat:
      parse<Heartbeat>(m);
      return;
    case MessageType::HeartbeatAck:
      parse<HeartbeatAck>(m);
      return;
    case MessageType::Error:
      parse<ErrorReport>(m);
      return;
    case MessageType::Bye:
      parse<Bye>(m);
      return;
    case MessageType::Prepare: {
      const Prepare p = parse<Prepare>(m);
      sg::DecodeLimits limits;
      limits.maxArrayElements = 1 << 20;
      sg::decode(p.changes, limits);
      return;
    }
  }
}

}  // namespace
}  // namespace tsr::cluster

namespace tsr::fuzz {

// Frames are cut from the stream by their headers, as a connection reads
// them; a refused header ends the stream as it ends a connection.
void clusterMessages(Bytes bytes) {
  using namespace tsr::cluster;
  while (bytes.size() >= kFrameHeaderBytes) {
    FrameHeader header;
    try {
      header = decodeFrameHeader(bytes.first(kFrameHeaderBytes));
    } catch (const ProtocolError&) {
      return;
    }
    bytes = bytes.subspan(kFrameHeaderBytes);
    if (header.length > bytes.size()) return;
    Message m{header.type, std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + header.length)};
    bytes = bytes.subspan(header.length);
    try {
      decodePayload(m);
    } catch (const ProtocolError&) {
    } catch (const sg::DecodeError&) {}
  }
}

}  // namespace tsr::fuzz
