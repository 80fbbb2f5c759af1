#pragma once
// Colour, depth and named outputs of one rectangle as RenderTile bytes:
// RGBA float, depth float, then RGBA float per named output (20 + 16 n
// bytes a pixel), compressed with lz4 or zstd when that makes the payload
// smaller (lossless, so tiles stay bitwise exact).
#include <cstdint>
#include <string>
#include <vector>

#include "tsr/cluster/messages.hpp"
#include "tsr/med/frame_buffer.hpp"

namespace tsr::cluster {

inline constexpr std::size_t kBytesPerPixel = 20;  // colour and depth
inline constexpr std::size_t kBytesPerOutputPixel = 16;
inline constexpr std::uint64_t kMaxTilePixels = kMaxRectPixels;
inline constexpr std::size_t kMaxDecodedTileBytes = std::size_t{1} << 30;

struct EncodedPixels {
  Compression compression = Compression::None;
  std::vector<std::uint8_t> bytes;
};

// Falls back to None when compression does not pay. Throws
// std::invalid_argument when fb lacks one of `outputs`.
EncodedPixels encodePixels(const med::FrameBuffer& fb, Compression preferred,
                           const std::vector<std::string>& outputs = {});
// Throws ProtocolError(Malformed) unless `bytes` decode to exactly
// width x height pixels of colour, depth and `outputs`.
med::FrameBuffer decodePixels(std::uint32_t width, std::uint32_t height, Compression compression,
                              const std::vector<std::uint8_t>& bytes, const std::vector<std::string>& outputs = {});

}  // namespace tsr::cluster
