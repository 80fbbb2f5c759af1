#pragma once
// A participating medium (Schwenk's CommonVolumeShader, 5.B): absorption
// and scattering coefficients per unit length, emitted radiance per unit
// length, and a Henyey–Greenstein phase function. Each coefficient may be
// multiplied by a 3D texture: `textureSlices` slices of equal height
// stacked top (lowest z) to bottom in one texture, each seen from +z
// (left: lowest x, top: highest y), stretched over the object-space
// bounding box of the mesh the medium fills (a scene-wide medium has
// none). A textured medium is heterogeneous and traced by delta tracking.
#include "tsr/embree/vocabulary.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>

namespace tsr::embree {

struct Medium {
  glm::vec3 absorption{0.0f};  // sigma_a
  glm::vec3 scattering{0.0f};  // sigma_s
  glm::vec3 emission{0.0f};    // radiance added per unit length
  float g = 0.0f;              // mean cosine of the phase function, clamped to +-0.99 when traced
  std::optional<TextureId> absorptionTexture;
  std::optional<TextureId> scatteringTexture;
  std::optional<TextureId> emissionTexture;
  std::uint32_t textureSlices = 1;  // 0 reads as 1

  glm::vec3 extinction() const { return absorption + scattering; }
  bool textured() const { return absorptionTexture || scatteringTexture || emissionTexture; }
  bool empty() const {
    const glm::vec3 t = extinction();
    return t.x <= 0.0f && t.y <= 0.0f && t.z <= 0.0f && emission.x <= 0.0f && emission.y <= 0.0f && emission.z <= 0.0f;
  }
};

}  // namespace tsr::embree
