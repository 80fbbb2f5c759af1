#pragma once

#include <glm/vec4.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace tsr::vk {

enum class TextureFormat {
  Rgba8Srgb,   // colour data: sRGB-decoded by the sampler, alpha linear
  Rgba8Unorm,  // linear 8-bit
  Rgba32F,     // linear float
};

// An RGBA image. Texel (0, 0) is the top-left one and uv (0, 0) its corner
// (glTF convention); lookups are bilinear and wrap (repeat) in both axes.
class Texture {
 public:
  static Texture fromRgba8(std::uint32_t width, std::uint32_t height, std::span<const std::uint8_t> rgba,
                           bool srgb = true);
  static Texture fromFloat(std::uint32_t width, std::uint32_t height, std::span<const glm::vec4> texels);

  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }
  TextureFormat format() const { return format_; }
  const std::vector<std::uint8_t>& bytes() const { return bytes_; }

 private:
  Texture(std::uint32_t width, std::uint32_t height, TextureFormat format, std::vector<std::uint8_t> bytes);

  std::uint32_t width_;
  std::uint32_t height_;
  TextureFormat format_;
  std::vector<std::uint8_t> bytes_;
};

}  // namespace tsr::vk
