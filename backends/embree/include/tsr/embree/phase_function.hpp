#pragma once
// The Henyey–Greenstein phase function (pbrt-v4, 11.3.1): the angular
// distribution of light scattered in a medium, with mean cosine g (g > 0
// forward, g < 0 backward, 0 isotropic). Directions here are both the
// ray's travel: `in` arrives, `out` leaves; cos = dot(in, out).
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "tsr/embree/sampling.hpp"

namespace tsr::embree {

inline constexpr float kMaxPhaseG = 0.99f;  // beyond, the lobe is a delta in all but name

inline float henyeyGreenstein(float cosTheta, float g) {
  g = std::clamp(g, -kMaxPhaseG, kMaxPhaseG);
  const float denom = 1.0f + g * g - 2.0f * g * cosTheta;
  return (1.0f - g * g) / (4.0f * kPi * denom * std::sqrt(std::max(denom, 1e-12f)));
}

// A direction leaving `in` with density henyeyGreenstein(dot(in, out), g);
// the density is the phase value itself.
inline glm::vec3 sampleHenyeyGreenstein(const glm::vec3& in, float g, const glm::vec2& u) {
  g = std::clamp(g, -kMaxPhaseG, kMaxPhaseG);
  float cosTheta;
  if (std::abs(g) < 1e-3f) {
    cosTheta = 1.0f - 2.0f * u.x;
  } else {
    const float s = (1.0f - g * g) / (1.0f - g + 2.0f * g * u.x);
    cosTheta = (1.0f + g * g - s * s) / (2.0f * g);
  }
  cosTheta = std::clamp(cosTheta, -1.0f, 1.0f);
  const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
  const float phi = 2.0f * kPi * u.y;
  const Frame frame(in);
  return glm::normalize(frame.toWorld({sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta}));
}

}  // namespace tsr::embree
