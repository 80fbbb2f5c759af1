#pragma once

#include <glm/vec3.hpp>

namespace tsr::vk {

// A homogeneous participating medium, per colour channel: absorption and
// scattering coefficients (1 / scene unit), emitted radiance per unit length,
// Henyey–Greenstein mean cosine g. The rasterizer approximates it (see
// docs/volumes.md, "In the rasterizer"): transmittance exp(-sigma_t d) over
// the distance a view ray travels in it, light scattered in once from the
// ambient term and the lights at the segment's midpoint, unshadowed.
struct Medium {
  glm::vec3 absorption{0.0f};
  glm::vec3 scattering{0.0f};
  glm::vec3 emission{0.0f};
  float g = 0.0f;

  glm::vec3 extinction() const { return absorption + scattering; }
  bool empty() const { return extinction() == glm::vec3(0.0f) && emission == glm::vec3(0.0f); }
};

}  // namespace tsr::vk
