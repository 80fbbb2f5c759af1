#pragma once
// Karis' prefilter of radiance by GGX roughness with n = v = r: half vectors
// from D around r (a Hammersley set of `samples`), reflected, weighted by
// n.l. Shared by the environment's levels (environment.cpp) and the
// reflection probe's (probe_prefilter.cpp); `radiance(l)` looks one up.
#include "reflections/radical_inverse.hpp"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace tsr::vk {

template <class Radiance>
glm::vec3 ggxPrefiltered(const glm::vec3& r, float roughness, std::uint32_t samples, const Radiance& radiance) {
  constexpr float kPi = std::numbers::pi_v<float>;
  const float a = std::max(1e-3f, roughness * roughness);
  const glm::vec3 up = std::abs(r.y) < 0.999f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 tx = glm::normalize(glm::cross(up, r)), ty = glm::cross(r, tx);
  glm::vec3 sum(0.0f);
  float weight = 0.0f;
  for (std::uint32_t s = 0; s < samples; ++s) {
    const float u1 = (float(s) + 0.5f) / float(samples), u2 = radicalInverse(s);
    const float cosH = std::sqrt((1.0f - u1) / (1.0f + (a * a - 1.0f) * u1));
    const float sinH = std::sqrt(std::max(0.0f, 1.0f - cosH * cosH));
    const float phi = 2.0f * kPi * u2;
    const glm::vec3 h = tx * (sinH * std::cos(phi)) + ty * (sinH * std::sin(phi)) + r * cosH;
    const glm::vec3 l = 2.0f * glm::dot(r, h) * h - r;
    const float nl = glm::dot(r, l);
    if (nl <= 0.0f) continue;
    sum += nl * radiance(l);
    weight += nl;
  }
  return weight > 0.0f ? sum / weight : radiance(r);
}

}  // namespace tsr::vk
