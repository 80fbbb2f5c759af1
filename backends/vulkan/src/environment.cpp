#include "tsr/vk/environment.hpp"

#include "tsr/vk/error.hpp"

#include <cmath>
#include <numbers>

namespace tsr::vk {

namespace {
bool finiteNonNegative(const glm::vec3& v) {
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(v[i]) || v[i] < 0.0f) return false;
  return true;
}
}  // namespace

Environment Environment::constant(const glm::vec3& radiance) {
  if (!finiteNonNegative(radiance)) throw Error("environment radiance must be finite and non-negative");
  Environment e;
  e.average_ = radiance;
  return e;
}

Environment Environment::latLong(std::uint32_t width, std::uint32_t height, std::span<const glm::vec4> texels,
                                 float scale) {
  if (width == 0 || height == 0 || texels.size() != std::size_t(width) * height)
    throw Error("environment map size does not match its texels");
  if (!std::isfinite(scale) || scale < 0.0f) throw Error("environment scale must be finite and non-negative");
  glm::dvec3 sum(0.0);
  double weight = 0.0;
  for (std::uint32_t y = 0; y < height; ++y) {
    // Row y spans polar angles [y, y+1] * pi / height; its solid angle is proportional to sin(theta).
    const double w = std::sin((y + 0.5) * std::numbers::pi / height);
    for (std::uint32_t x = 0; x < width; ++x) {
      const glm::vec4& t = texels[std::size_t(y) * width + x];
      if (!finiteNonNegative(glm::vec3(t))) throw Error("environment map texels must be finite and non-negative");
      sum += w * glm::dvec3(t);
      weight += w;
    }
  }
  Environment e;
  e.average_ = glm::vec3(sum / weight) * scale;
  return e;
}

Environment Environment::withFog(const Medium& fog) const {
  if (!finiteNonNegative(fog.absorption) || !finiteNonNegative(fog.scattering) || !finiteNonNegative(fog.emission))
    throw Error("fog coefficients must be finite and non-negative");
  if (!(std::abs(fog.g) < 1.0f)) throw Error("fog phase g must be in (-1, 1)");
  Environment e = *this;
  e.fog_ = fog.empty() ? std::nullopt : std::optional<Medium>(fog);
  return e;
}

}  // namespace tsr::vk
