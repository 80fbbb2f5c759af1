#pragma once
// Every message on the wire is one frame:
//   "TSRN"  version u8  type u8  payload-length u32 (little-endian)   10 bytes
//   payload
// The header is checked before a single payload byte is read or allocated.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "tsr/cluster/message_type.hpp"

namespace tsr::cluster {

// 2: ErrorReport carries a kind byte before its reason (clients decide by
// the kind, never by the text).
// 3: scenes carry volume materials (container type 10), Geometry.volume
// and Background.medium.
// 4: RenderTile carries the samples per pixel its tile holds, the rays it
// cast and the seconds spent catching up (the client's workload figures);
// views carry a thin lens (aperture radius, focus distance).
// 5: views carry a shutter (open, close) and the camera's pose at the end
// of the frame interval; Transforms carry frameMotion.
// 6: Geometry carries its primitive (triangles, lines or points).
inline constexpr std::uint8_t kProtocolVersion = 6;
inline constexpr std::size_t kFrameHeaderBytes = 10;
inline constexpr std::array<std::uint8_t, 4> kFrameMagic{'T', 'S', 'R', 'N'};

struct FrameHeader {
  std::uint8_t version = kProtocolVersion;
  MessageType type{};
  std::uint32_t length = 0;
};

// Throws ProtocolError: BadMagic, VersionMismatch (a Hello of another
// version still decodes into `rawVersion` so a node can say why it refuses),
// UnknownType, Oversized.
FrameHeader decodeFrameHeader(std::span<const std::uint8_t> bytes, std::uint8_t expectedVersion = kProtocolVersion);
void writeFrameHeader(std::vector<std::uint8_t>& out, const FrameHeader& header);

}  // namespace tsr::cluster
