#pragma once
// A textured (heterogeneous) medium as the tracer reads it: its textures'
// texels, their slices, and the majorant, the largest extinction anywhere
// in it, that delta and ratio tracking sample tentative collisions with.
#include "tsr/embree/medium.hpp"
#include "tsr/embree/texture.hpp"

#include <glm/vec3.hpp>

namespace tsr::embree {

struct MediumCoefficients {
  glm::vec3 absorption;
  glm::vec3 scattering;
  glm::vec3 emission;
  glm::vec3 extinction() const { return absorption + scattering; }
};

class VolumeField {
 public:
  VolumeField() = default;
  VolumeField(const Medium& medium, const Texture* absorption, const Texture* scattering, const Texture* emission);

  bool active() const { return active_; }
  float majorant() const { return majorant_; }
  // The coefficients at a point of the unit cube (the bounding box the
  // textures stretch over); trilinear, clamped to the edge texels.
  MediumCoefficients at(const Medium& medium, const glm::vec3& unit) const;

 private:
  glm::vec3 sample(const Texture* t, const glm::vec3& unit) const;

  const Texture* absorption_ = nullptr;
  const Texture* scattering_ = nullptr;
  const Texture* emission_ = nullptr;
  std::uint32_t slices_ = 1;
  float majorant_ = 0.0f;
  bool active_ = false;
};

}  // namespace tsr::embree
