#pragma once

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace tsr::embree {

// An RGBA image in linear float. Texel (0, 0) is the top-left one and uv
// (0, 0) its corner (glTF convention); lookups wrap (repeat) in both axes.
class Texture {
 public:
  Texture(std::uint32_t width, std::uint32_t height, std::vector<glm::vec4> texels);

  // 8-bit RGBA; colour data is usually sRGB-encoded, so it is decoded to
  // linear unless srgb is false (alpha is always linear).
  static Texture fromRgba8(std::uint32_t width, std::uint32_t height, std::span<const std::uint8_t> rgba,
                           bool srgb = true);

  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }
  const glm::vec4& texel(std::uint32_t x, std::uint32_t y) const { return texels_[std::size_t(y) * width_ + x]; }
  const std::vector<glm::vec4>& texels() const { return texels_; }
  bool opaque() const { return opaque_; }  // every alpha is 1 or more

  glm::vec4 sampleBilinear(const glm::vec2& uv) const;
  glm::vec4 sampleNearest(const glm::vec2& uv) const;

 private:
  std::uint32_t width_;
  std::uint32_t height_;
  std::vector<glm::vec4> texels_;
  bool opaque_ = true;
};

}  // namespace tsr::embree
