#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace tsr::embree {

struct ElementSet;

// Indirect irradiance (W/m^2 per channel) reconstructed on the photon
// elements of one frame (PhotonSequence::reconstruct), for
// Renderer::renderWithIrradiance. Each element keeps a value at its three
// corners: the area-weighted mean of the elements around that corner whose
// normal is within the crease angle, so the lookup is continuous across
// element borders on smooth surfaces and does not bleed round sharp edges.
// Immutable once built; cheap to copy (the element topology is shared).
class Scene;

class IrradianceField {
 public:
  IrradianceField() = default;

  bool empty() const { return !elements_; }
  std::uint64_t sceneUid() const { return sceneUid_; }
  // True when `scene` has the elements this field was reconstructed on: the
  // same instances of meshes with the same triangle counts. The scene the
  // photons were traced in qualifies, and so does another copy of it posed
  // at another frame (a renderer lagging the photon pass by its lookahead).
  // Reads the scene as last committed.
  bool fits(const Scene& scene) const;
  // Changes with every reconstruction, so a renderer can tell fields apart.
  std::uint64_t uid() const { return uid_; }
  std::size_t elementCount() const { return element_.size(); }
  // The filtered irradiance of one element (for tests and diagnostics).
  glm::vec3 element(std::size_t e) const { return element_[e]; }

  // Irradiance at barycentrics (b1, b2) of triangle prim of an instance
  // (Embree's hit u, v); zero where there is no element.
  glm::vec3 at(std::uint32_t instance, std::uint32_t prim, float b1, float b2) const;

 private:
  friend class PhotonSequence;
  std::shared_ptr<const ElementSet> elements_;
  std::vector<glm::vec3> element_;
  std::vector<glm::vec3> corner_;  // 3 per element
  std::uint64_t sceneUid_ = 0;
  std::uint64_t uid_ = 0;
};

}  // namespace tsr::embree
