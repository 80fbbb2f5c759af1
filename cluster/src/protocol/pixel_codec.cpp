#include "tsr/cluster/pixel_codec.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

#include <lz4.h>
#include <zstd.h>

#include "tsr/cluster/protocol_error.hpp"

namespace tsr::cluster {

namespace {

std::vector<std::uint8_t> raw(const med::FrameBuffer& fb, const std::vector<std::string>& outputs) {
  std::size_t n = std::size_t{fb.width} * fb.height;
  std::vector<std::uint8_t> out(n * (kBytesPerPixel + outputs.size() * kBytesPerOutputPixel));
  std::memcpy(out.data(), fb.colour.data(), n * 16);
  std::memcpy(out.data() + n * 16, fb.depth.data(), n * 4);
  std::size_t at = n * kBytesPerPixel;
  for (const auto& name : outputs) {
    auto it = fb.outputs.find(name);
    if (it == fb.outputs.end() || it->second.size() != n)
      throw std::invalid_argument("the back-end did not fill output '" + name + "'");
    std::memcpy(out.data() + at, it->second.data(), n * kBytesPerOutputPixel);
    at += n * kBytesPerOutputPixel;
  }
  return out;
}

[[noreturn]] void malformed(const std::string& why) {
  throw ProtocolError(ProtocolError::Kind::Malformed, "RenderTile pixels: " + why);
}

}  // namespace

EncodedPixels encodePixels(const med::FrameBuffer& fb, Compression preferred, const std::vector<std::string>& outputs) {
  std::vector<std::uint8_t> plain = raw(fb, outputs);
  EncodedPixels out;
  if (preferred == Compression::Lz4 && plain.size() <= LZ4_MAX_INPUT_SIZE) {
    std::vector<std::uint8_t> packed(LZ4_compressBound(static_cast<int>(plain.size())));
    int n = LZ4_compress_default(reinterpret_cast<const char*>(plain.data()), reinterpret_cast<char*>(packed.data()),
                                 static_cast<int>(plain.size()), static_cast<int>(packed.size()));
    if (n > 0 && static_cast<std::size_t>(n) < plain.size()) {
      packed.resize(static_cast<std::size_t>(n));
      return {Compression::Lz4, std::move(packed)};
    }
  } else if (preferred == Compression::Zstd) {
    std::vector<std::uint8_t> packed(ZSTD_compressBound(plain.size()));
    std::size_t n = ZSTD_compress(packed.data(), packed.size(), plain.data(), plain.size(), 3);
    if (!ZSTD_isError(n) && n < plain.size()) {
      packed.resize(n);
      return {Compression::Zstd, std::move(packed)};
    }
  }
  out.bytes = std::move(plain);
  return out;
}

med::FrameBuffer decodePixels(std::uint32_t width, std::uint32_t height, Compression compression,
                              const std::vector<std::uint8_t>& bytes, const std::vector<std::string>& outputs) {
  std::uint64_t pixels = std::uint64_t{width} * height;
  if (pixels == 0 || pixels > kMaxTilePixels) malformed("tile of " + std::to_string(pixels) + " pixels");
  if (outputs.size() > kMaxOutputs) malformed(std::to_string(outputs.size()) + " named outputs");
  std::size_t expected = static_cast<std::size_t>(pixels) * (kBytesPerPixel + outputs.size() * kBytesPerOutputPixel);
  // As large as a RenderTile may be: a tile's header cannot make us allocate more.
  if (expected > kMaxDecodedTileBytes)
    malformed(std::to_string(expected) + " bytes of pixels, more than a tile may hold");
  std::vector<std::uint8_t> plain;
  const std::vector<std::uint8_t>* src = &bytes;
  switch (compression) {
    case Compression::None:
      if (bytes.size() != expected)
        malformed("expected " + std::to_string(expected) + " bytes, got " + std::to_string(bytes.size()));
      break;
    case Compression::Lz4: {
      if (bytes.size() > static_cast<std::size_t>(LZ4_MAX_INPUT_SIZE)) malformed("lz4 block too large");
      plain.resize(expected);
      int n = LZ4_decompress_safe(reinterpret_cast<const char*>(bytes.data()), reinterpret_cast<char*>(plain.data()),
                                  static_cast<int>(bytes.size()), static_cast<int>(expected));
      if (n < 0 || static_cast<std::size_t>(n) != expected) malformed("lz4 data does not decode to the tile size");
      src = &plain;
      break;
    }
    case Compression::Zstd: {
      unsigned long long size = ZSTD_getFrameContentSize(bytes.data(), bytes.size());
      if (size != expected) malformed("zstd frame does not announce the tile size");
      plain.resize(expected);
      std::size_t n = ZSTD_decompress(plain.data(), plain.size(), bytes.data(), bytes.size());
      if (ZSTD_isError(n) || n != expected) malformed("zstd data does not decode to the tile size");
      src = &plain;
      break;
    }
    default:  // a byte no encoder writes must not pass as raw pixels of any length
      malformed("unknown compression " + std::to_string(static_cast<int>(compression)));
  }
  med::FrameBuffer fb(width, height);
  std::memcpy(static_cast<void*>(fb.colour.data()), src->data(), static_cast<std::size_t>(pixels) * 16);
  std::memcpy(fb.depth.data(), src->data() + pixels * 16, static_cast<std::size_t>(pixels) * 4);
  std::size_t at = static_cast<std::size_t>(pixels) * kBytesPerPixel;
  for (const auto& name : outputs) {
    auto& image = fb.outputs[name];
    image.resize(static_cast<std::size_t>(pixels));
    std::memcpy(static_cast<void*>(image.data()), src->data() + at, image.size() * kBytesPerOutputPixel);
    at += image.size() * kBytesPerOutputPixel;
  }
  return fb;
}

}  // namespace tsr::cluster
