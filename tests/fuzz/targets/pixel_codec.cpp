#include <cstdlib>
#include <cstring>

#include "fuzz_targets.hpp"
#include "tsr/cluster/pixel_codec.hpp"
#include "tsr/cluster/protocol_error.hpp"

namespace tsr::fuzz {

// Four leading bytes choose width and height (1..64), the compression
// (including values no encoder writes) and how many named outputs the tile
// claims; the rest are the pixel bytes.
void pixelCodec(Bytes bytes) {
  using namespace tsr::cluster;
  if (bytes.size() < 4) return;
  const std::uint32_t width = 1 + bytes[0] % 64, height = 1 + bytes[1] % 64;
  const auto compression = static_cast<Compression>(bytes[2] % 4);
  static const std::vector<std::string> kNames{"albedo", "normal", "variance"};
  const std::vector<std::string> outputs(kNames.begin(), kNames.begin() + bytes[3] % 4);
  const std::vector<std::uint8_t> pixels(bytes.begin() + 4, bytes.end());
  med::FrameBuffer fb;
  try {
    fb = decodePixels(width, height, compression, pixels, outputs);
  } catch (const ProtocolError&) {
    return;
  }
  // Lossless: what decoded encodes and decodes to the same bits.
  const EncodedPixels again =
      encodePixels(fb, compression == Compression::Zstd ? Compression::Zstd : Compression::Lz4, outputs);
  const med::FrameBuffer back = decodePixels(width, height, again.compression, again.bytes, outputs);
  const auto same = [](const auto& a, const auto& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
  };
  if (!same(back.colour, fb.colour) || !same(back.depth, fb.depth)) std::abort();
  for (const std::string& name : outputs)
    if (!same(back.outputs.at(name), fb.outputs.at(name))) std::abort();
}

}  // namespace tsr::fuzz
