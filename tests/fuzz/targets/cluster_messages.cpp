#include "fuzz_targets.hpp"
#include "tsr/cluster/frame_header.hpp"
#include "tsr/cluster/messages.hpp"
#include "tsr/cluster/pixel_codec.hpp"
#include "tsr/cluster/protocol_error.hpp"
#include "tsr/sg/errors.hpp"
#include "tsr/sg/wire/wire_codec.hpp"

namespace tsr::cluster {
namespace {

// What a node or client does with a payload of this type: parse it (every
// type of the message list), and for bulk data decode what it carries.
void decodePayload(const Message& m) {
  Messages::visit(m.type, [&]<class M>() {
    const M decoded = parse<M>(m);
    if constexpr (std::is_same_v<M, Snapshot> || std::is_same_v<M, Changes> || std::is_same_v<M, Prepare>) {
      sg::DecodeLimits limits;
      limits.maxArrayElements = 1 << 20;
      sg::decode(decoded.changes, limits);
    } else if constexpr (std::is_same_v<M, RenderTile>) {
      decodePixels(decoded.rect.width(), decoded.rect.height(), decoded.compression, decoded.pixels, decoded.outputs);
    }
  });
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
