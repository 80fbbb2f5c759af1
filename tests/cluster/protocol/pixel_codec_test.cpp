// Tile pixels: lossless through every compression, bounded on decode.
#include <random>

#include <gtest/gtest.h>

#include "tsr/cluster/pixel_codec.hpp"
#include "tsr/cluster/protocol_error.hpp"

namespace tsr::cluster {
namespace {

med::FrameBuffer pattern(std::uint32_t w, std::uint32_t h, bool noisy) {
  med::FrameBuffer fb(w, h);
  std::mt19937 rng(5);
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x) {
      float v = noisy ? std::uniform_real_distribution<float>(0, 1)(rng) : (x < w / 2 ? 0.25f : 0.75f);
      fb.colour[fb.index(x, y)] = glm::vec4(v, v * 0.5f, 1 - v, 1);
      fb.depth[fb.index(x, y)] = (x + y) % 3 ? 2.5f : med::kNoDepth;
    }
  return fb;
}

bool bitwiseEqual(const med::FrameBuffer& a, const med::FrameBuffer& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.colour.data(), b.colour.data(), a.colour.size() * sizeof(glm::vec4)) == 0 &&
         std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * sizeof(float)) == 0;
}

TEST(PixelCodec, LosslessForEveryCompression) {
  for (bool noisy : {false, true})
    for (Compression c : {Compression::None, Compression::Lz4, Compression::Zstd}) {
      med::FrameBuffer fb = pattern(37, 21, noisy);
      EncodedPixels e = encodePixels(fb, c);
      EXPECT_TRUE(bitwiseEqual(decodePixels(37, 21, e.compression, e.bytes), fb));
    }
}

TEST(PixelCodec, CompressesWhereItPays) {
  med::FrameBuffer flat = pattern(64, 64, false);
  EXPECT_EQ(encodePixels(flat, Compression::Lz4).compression, Compression::Lz4);
  EXPECT_LT(encodePixels(flat, Compression::Zstd).bytes.size(), 64u * 64 * kBytesPerPixel / 10);
  EXPECT_EQ(encodePixels(flat, Compression::None).bytes.size(), 64u * 64 * kBytesPerPixel);
}

TEST(PixelCodec, WrongSizesAndGarbageAreMalformed) {
  med::FrameBuffer fb = pattern(16, 16, false);
  for (Compression c : {Compression::None, Compression::Lz4, Compression::Zstd}) {
    EncodedPixels e = encodePixels(fb, c);
    EXPECT_THROW(decodePixels(16, 15, e.compression, e.bytes), ProtocolError);
    EXPECT_THROW(decodePixels(17, 16, e.compression, e.bytes), ProtocolError);
    auto cut = e.bytes;
    cut.resize(cut.size() / 2);
    EXPECT_THROW(decodePixels(16, 16, e.compression, cut), ProtocolError);
  }
  std::vector<std::uint8_t> garbage(300, 0xab);
  EXPECT_THROW(decodePixels(16, 16, Compression::Lz4, garbage), ProtocolError);
  EXPECT_THROW(decodePixels(16, 16, Compression::Zstd, garbage), ProtocolError);
  EXPECT_THROW(decodePixels(1u << 15, 1u << 15, Compression::None, garbage), ProtocolError);
}

// Found by fuzz_pixel_codec: a compression byte outside the enum fell
// through the switch and the payload was read as raw pixels of any length.
TEST(PixelCodec, UnknownCompressionIsMalformedWhateverTheLength) {
  const std::vector<std::uint8_t> few(4, 0);
  const std::vector<std::uint8_t> exact(16 * 16 * kBytesPerPixel, 0);
  EXPECT_THROW(decodePixels(16, 16, static_cast<Compression>(3), few), ProtocolError);
  EXPECT_THROW(decodePixels(16, 16, static_cast<Compression>(3), exact), ProtocolError);
}

}  // namespace
}  // namespace tsr::cluster
