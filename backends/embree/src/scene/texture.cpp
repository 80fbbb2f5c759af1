#include "tsr/embree/texture.hpp"

#include "tsr/embree/error.hpp"

#include <cmath>
#include <string>

namespace tsr::embree {

namespace {
float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

std::uint32_t wrap(int i, std::uint32_t n) {
  int m = i % int(n);
  return std::uint32_t(m < 0 ? m + int(n) : m);
}
}  // namespace

Texture::Texture(std::uint32_t width, std::uint32_t height, std::vector<glm::vec4> texels)
    : width_(width), height_(height), texels_(std::move(texels)) {
  if (width == 0 || height == 0) throw Error("texture size must be non-zero");
  if (texels_.size() != std::size_t(width) * height) {
    throw Error("texture has " + std::to_string(texels_.size()) + " texels, expected " +
                std::to_string(std::size_t(width) * height));
  }
  for (const auto& t : texels_) {
    if (!std::isfinite(t.x) || !std::isfinite(t.y) || !std::isfinite(t.z) || !std::isfinite(t.w)) {
      throw Error("texture contains a non-finite texel");
    }
    opaque_ = opaque_ && t.w >= 1.0f;
  }
}

Texture Texture::fromRgba8(std::uint32_t width, std::uint32_t height, std::span<const std::uint8_t> rgba, bool srgb) {
  if (rgba.size() != std::size_t(width) * height * 4)
    throw Error("8-bit texture data size does not match width*height*4");
  std::vector<glm::vec4> texels(std::size_t(width) * height);
  for (std::size_t i = 0; i < texels.size(); ++i) {
    glm::vec4 t;
    for (int c = 0; c < 4; ++c) {
      float v = float(rgba[4 * i + c]) / 255.0f;
      t[c] = (srgb && c < 3) ? srgbToLinear(v) : v;
    }
    texels[i] = t;
  }
  return Texture(width, height, std::move(texels));
}

glm::vec4 Texture::sampleNearest(const glm::vec2& uv) const {
  int x = int(std::floor(uv.x * float(width_)));
  int y = int(std::floor(uv.y * float(height_)));
  return texel(wrap(x, width_), wrap(y, height_));
}

glm::vec4 Texture::sampleBilinear(const glm::vec2& uv) const {
  float fx = uv.x * float(width_) - 0.5f;
  float fy = uv.y * float(height_) - 0.5f;
  if (!std::isfinite(fx) || !std::isfinite(fy)) return texel(0, 0);
  float x0f = std::floor(fx);
  float y0f = std::floor(fy);
  float tx = fx - x0f;
  float ty = fy - y0f;
  // Reduce before converting so huge uvs cannot overflow int.
  int x0 = int(std::fmod(x0f, float(width_)));
  int y0 = int(std::fmod(y0f, float(height_)));
  std::uint32_t xa = wrap(x0, width_), xb = wrap(x0 + 1, width_);
  std::uint32_t ya = wrap(y0, height_), yb = wrap(y0 + 1, height_);
  glm::vec4 top = texel(xa, ya) * (1.0f - tx) + texel(xb, ya) * tx;
  glm::vec4 bottom = texel(xa, yb) * (1.0f - tx) + texel(xb, yb) * tx;
  return top * (1.0f - ty) + bottom * ty;
}

}  // namespace tsr::embree
