#pragma once
// Colour + depth of one rectangle as RenderTile bytes: RGBA float then
// depth float, 20 bytes a pixel, compressed with lz4 or zstd when that
// makes the payload smaller (lossless, so tiles stay bitwise exact).
#include <cstdint>
#include <vector>

#include "tsr/cluster/messages.hpp"
#include "tsr/med/frame_buffer.hpp"

namespace tsr::cluster {

inline constexpr std::size_t kBytesPerPixel = 20;
inline constexpr std::uint64_t kMaxTilePixels = kMaxRectPixels;

struct EncodedPixels {
  Compression compression = Compression::None;
  std::vector<std::uint8_t> bytes;
};

// Falls back to None when compression does not pay.
EncodedPixels encodePixels(const med::FrameBuffer& fb, Compression preferred);
// Throws ProtocolError(Malformed) unless `bytes` decode to exactly
// width x height pixels.
med::FrameBuffer decodePixels(std::uint32_t width, std::uint32_t height, Compression compression,
                              const std::vector<std::uint8_t>& bytes);

}  // namespace tsr::cluster
