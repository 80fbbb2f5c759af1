#include "tsr/med/scene_values.hpp"

#include <cmath>
#include <cstring>

#include <glm/glm.hpp>

namespace tsr::med {

std::vector<glm::vec4> linearTexels(const sg::Image& image) {
  const std::uint32_t n = image.channels();
  std::vector<glm::vec4> texels(std::size_t{image.width()} * image.height(), glm::vec4(0, 0, 0, 1));
  const bool srgb = image.colorSpace() == sg::ColorSpace::SRGB;
  auto decode = [](float v) { return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f); };
  // Channels that hold colour: grey alone, or red, green and blue; never alpha.
  const std::uint32_t colourChannels = n <= 2 ? 1 : 3;
  for (std::size_t i = 0; i < texels.size(); ++i) {
    for (std::uint32_t c = 0; c < n; ++c) {
      float v;
      if (image.format() == sg::PixelFormat::Float32) {
        std::memcpy(&v, image.pixels().data() + (i * n + c) * 4, 4);
      } else {
        v = static_cast<float>(image.pixels()[i * n + c]) / 255.0f;
        if (srgb && c < colourChannels) v = decode(v);
      }
      texels[i][static_cast<int>(c)] = v;
    }
    if (n == 1) texels[i] = glm::vec4(texels[i].r, texels[i].r, texels[i].r, 1.0f);
    if (n == 2) texels[i] = glm::vec4(texels[i].r, texels[i].r, texels[i].r, texels[i].g);
  }
  return texels;
}

BakedSky bakeGradient(const sg::Background& background) {
  BakedSky sky;
  sky.texels.resize(std::size_t{sky.width} * sky.height);
  for (std::uint32_t y = 0; y < sky.height; ++y) {
    float t = (static_cast<float>(y) + 0.5f) / static_cast<float>(sky.height);  // 0 at the zenith
    glm::vec3 c = glm::mix(background.gradientTop(), background.gradientBottom(), t);
    for (std::uint32_t x = 0; x < sky.width; ++x) sky.texels[y * sky.width + x] = glm::vec4(c, 1.0f);
  }
  return sky;
}

std::pair<glm::vec3, glm::vec3> usableUvTransform(const sg::SurfaceMaterial& s, sg::TextureSlot slot) {
  const auto [row0, row1] = s.uvTransform(slot);
  auto finite = [](const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  if (!finite(row0) || !finite(row1)) return {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)};
  return {row0, row1};
}

SurfaceClass classify(const sg::SurfaceMaterial& s) {
  if (s.transmission() > 0.5f) return s.roughness() < 0.05f ? SurfaceClass::Glass : SurfaceClass::Dielectric;
  if (s.metallic() > 0.5f) return s.roughness() < 0.02f ? SurfaceClass::Mirror : SurfaceClass::Conductor;
  return SurfaceClass::Diffuse;
}

}  // namespace tsr::med
