#pragma once
// A homogeneous participating medium (Schwenk's CommonVolumeShader, 5.B):
// absorption and scattering coefficients per unit length, emitted
// radiance per unit length, and a Henyey–Greenstein phase function.
#include <glm/vec3.hpp>

namespace tsr::embree {

struct Medium {
  glm::vec3 absorption{0.0f};  // sigma_a
  glm::vec3 scattering{0.0f};  // sigma_s
  glm::vec3 emission{0.0f};    // radiance added per unit length
  float g = 0.0f;              // mean cosine of the phase function, clamped to +-0.99 when traced

  glm::vec3 extinction() const { return absorption + scattering; }
  bool empty() const {
    const glm::vec3 t = extinction();
    return t.x <= 0.0f && t.y <= 0.0f && t.z <= 0.0f && emission.x <= 0.0f && emission.y <= 0.0f && emission.z <= 0.0f;
  }
};

}  // namespace tsr::embree
