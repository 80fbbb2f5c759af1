#include "tsr/vk/texture.hpp"

#include "tsr/vk/error.hpp"

#include <cmath>
#include <cstring>
#include <string>

namespace tsr::vk {

namespace {
void checkSize(std::uint32_t width, std::uint32_t height, std::size_t have, std::size_t perTexel) {
  if (width == 0 || height == 0) throw Error("texture size must be non-zero");
  if (width > 16384 || height > 16384) throw Error("texture larger than 16384 texels on a side");
  const std::size_t want = std::size_t(width) * height * perTexel;
  if (have != want) {
    throw Error("texture data has " + std::to_string(have) + " values, expected " + std::to_string(want) + " for " +
                std::to_string(width) + "x" + std::to_string(height));
  }
}
}  // namespace

Texture::Texture(std::uint32_t width, std::uint32_t height, TextureFormat format, std::vector<std::uint8_t> bytes)
    : width_(width), height_(height), format_(format), bytes_(std::move(bytes)) {}

Texture Texture::fromRgba8(std::uint32_t width, std::uint32_t height, std::span<const std::uint8_t> rgba, bool srgb) {
  checkSize(width, height, rgba.size(), 4);
  return Texture(width, height, srgb ? TextureFormat::Rgba8Srgb : TextureFormat::Rgba8Unorm,
                 std::vector<std::uint8_t>(rgba.begin(), rgba.end()));
}

Texture Texture::fromFloat(std::uint32_t width, std::uint32_t height, std::span<const glm::vec4> texels) {
  checkSize(width, height, texels.size(), 1);
  for (const glm::vec4& t : texels)
    if (!std::isfinite(t.x) || !std::isfinite(t.y) || !std::isfinite(t.z) || !std::isfinite(t.w))
      throw Error("texture contains NaN or infinity");
  std::vector<std::uint8_t> bytes(texels.size_bytes());
  std::memcpy(bytes.data(), texels.data(), bytes.size());
  return Texture(width, height, TextureFormat::Rgba32F, std::move(bytes));
}

}  // namespace tsr::vk
