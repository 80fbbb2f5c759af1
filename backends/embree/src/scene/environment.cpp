#include "tsr/embree/environment.hpp"

#include "tsr/embree/distribution.hpp"
#include "tsr/embree/error.hpp"
#include "tsr/embree/sampling.hpp"

#include <cmath>
#include <optional>

namespace tsr::embree {

struct Environment::Impl {
  glm::vec3 colour{0.0f};
  std::optional<Texture> map;
  float scale = 1.0f;
  Distribution2D distribution;
};

Environment::Environment() : impl_(std::make_shared<Impl>()) {}

Environment Environment::constant(const glm::vec3& radiance) {
  if (!std::isfinite(radiance.x) || !std::isfinite(radiance.y) || !std::isfinite(radiance.z) || radiance.x < 0.0f ||
      radiance.y < 0.0f || radiance.z < 0.0f) {
    throw Error("environment radiance must be finite and non-negative");
  }
  auto impl = std::make_shared<Impl>();
  impl->colour = radiance;
  Environment env;
  env.impl_ = std::move(impl);
  return env;
}

Environment Environment::latLong(const Texture& map, float scale) {
  if (!std::isfinite(scale) || scale < 0.0f) throw Error("environment scale must be finite and non-negative");
  auto impl = std::make_shared<Impl>();
  impl->map = map;
  impl->scale = scale;
  // Weight texels by luminance and by the solid angle of their row (sin theta).
  std::vector<float> weights(std::size_t(map.width()) * map.height());
  for (std::uint32_t y = 0; y < map.height(); ++y) {
    float sinTheta = std::sin(kPi * (float(y) + 0.5f) / float(map.height()));
    for (std::uint32_t x = 0; x < map.width(); ++x) {
      glm::vec3 c(map.texel(x, y));
      if (c.x < 0.0f || c.y < 0.0f || c.z < 0.0f) throw Error("environment map has negative radiance");
      weights[std::size_t(y) * map.width() + x] = std::max(luminance(c), 0.0f) * sinTheta;
    }
  }
  impl->distribution = Distribution2D(weights, map.width(), map.height());
  Environment env;
  env.impl_ = std::move(impl);
  return env;
}

bool Environment::isBlack() const {
  if (impl_->map) return impl_->scale <= 0.0f || impl_->distribution.empty();
  return maxComponent(impl_->colour) <= 0.0f;
}

glm::vec2 Environment::directionToUv(const glm::vec3& d) {
  float u = std::atan2(d.x, -d.z) / (2.0f * kPi) + 0.5f;
  float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi;
  return {u, v};
}

glm::vec3 Environment::uvToDirection(const glm::vec2& uv) {
  float phi = (uv.x - 0.5f) * 2.0f * kPi;
  float theta = uv.y * kPi;
  float s = std::sin(theta);
  return {s * std::sin(phi), std::cos(theta), -s * std::cos(phi)};
}

glm::vec3 Environment::radiance(const glm::vec3& direction) const {
  // Piecewise constant, matching the sampling density exactly.
  if (impl_->map) return glm::vec3(impl_->map->sampleNearest(directionToUv(direction))) * impl_->scale;
  return impl_->colour;
}

Environment::Sample Environment::sample(const glm::vec2& u) const {
  Sample s;
  if (isBlack()) return s;
  if (!impl_->map) {
    s.direction = sampleUniformSphere(u);
    s.radiance = impl_->colour;
    s.pdf = kUniformSpherePdf;
    return s;
  }
  float pdfUv = 0.0f;
  glm::vec2 uv = impl_->distribution.sample(u, &pdfUv);
  float sinTheta = std::sin(uv.y * kPi);
  if (pdfUv <= 0.0f || sinTheta <= 0.0f) return s;
  s.direction = uvToDirection(uv);
  s.radiance = glm::vec3(impl_->map->sampleNearest(uv)) * impl_->scale;
  s.pdf = pdfUv / (2.0f * kPi * kPi * sinTheta);
  return s;
}

float Environment::pdf(const glm::vec3& direction) const {
  if (isBlack()) return 0.0f;
  if (!impl_->map) return kUniformSpherePdf;
  glm::vec2 uv = directionToUv(direction);
  float sinTheta = std::sin(uv.y * kPi);
  if (sinTheta <= 0.0f) return 0.0f;
  return impl_->distribution.pdf(uv) / (2.0f * kPi * kPi * sinTheta);
}

}  // namespace tsr::embree
