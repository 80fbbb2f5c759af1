#pragma once
// One frame's photons: emitted from the point, spot and directional lights
// and the emissive triangles in proportion to their luminous power, all of
// (about) the same energy, followed through the scene; every hit on a
// Diffuse surface after the first scattering event (light arriving
// indirectly, caustics included) is recorded on its element. Private.
#include "photons/photon_elements.hpp"

#include <oneapi/tbb/task_arena.h>

#include <cstdint>
#include <vector>

namespace tsr::embree {

struct PhotonHit {
  std::uint32_t element;
  std::uint32_t parity;  // photon index & 1: the even and odd half-sets
  glm::vec3 power;
};

// Total emitted power (W per channel) of the scene's lights at its current
// pose; a directional light counts over the disc covering `bounds`.
glm::vec3 emittedPower(const SceneState& scene, const ElementGeometry& bounds);
// The same per source (each light, each emissive triangle), in scene order.
std::vector<glm::vec3> sourcePowers(const SceneState& scene, const ElementGeometry& bounds);

struct PhotonPassResult {
  std::vector<PhotonHit> hits;  // in photon order: independent of the thread count
  std::uint64_t rays = 0;
};

// Traces `photons` photons with random streams keyed by streamKey.
PhotonPassResult tracePhotons(const SceneState& scene, const ElementSet& elements, const ElementGeometry& geometry,
                              std::uint64_t photons, std::uint64_t streamKey, std::uint32_t maxBounces,
                              tbb::task_arena& arena);

}  // namespace tsr::embree
