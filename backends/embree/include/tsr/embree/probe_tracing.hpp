#pragma once

#include "tsr/backend/irradiance_volume.hpp"
#include "tsr/embree/render_settings.hpp"
#include "tsr/embree/scene.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tsr::embree {

// Fills probes of an irradiance volume (tsr/backend/irradiance_volume.hpp)
// with the path tracer's light, for a back-end that cannot trace: from each
// probe, paths in directions spread evenly over the sphere (the same number
// through every texel of its distance map), traced as camera paths are with
// `settings` (depth, roulette, sampler, seed). What a path brings back is
// the radiance arriving at the probe, less an emitter's emission seen
// straight from it (the reader lights with emitters directly; an emitter
// seen in a mirror or through glass stays: its caustic is the probe's); its first
// hit's distance goes into the distance map, and a probe of which more than
// a quarter of the first hits are back faces gets weight 0 (it is inside
// something).
//
// What a probe's paths added up to so far (traceProbes continues them).
struct ProbeSums {
  std::array<glm::vec3, backend::IrradianceVolume::kFaces> faces{};  // radiance x cosine to each face
  std::array<glm::vec2, backend::IrradianceVolume::kDistanceTexels> distance{};
  std::uint32_t backFaces = 0;
  std::uint32_t paths = 0;
};

// Adds `paths` paths (rounded up to a multiple of kDistanceTexels) to each
// of probes first .. first + count - 1 (wrapping round the volume's end),
// continuing each probe's sequence where its sums left off (zeroed sums
// start it anew), writes those probes' values into the volume from their
// sums, and bumps volume.version. sums holds one entry per probe. A
// probe's paths depend on the seed, its index and position and its count
// so far only, so the same calls over the same scene give the same volume
// on every node. Commits the scene; parallel over probes. Returns the rays
// cast.
std::uint64_t traceProbes(Scene& scene, const RenderSettings& settings, backend::IrradianceVolume& volume,
                          std::vector<ProbeSums>& sums, std::size_t first, std::size_t count, std::uint32_t paths);

}  // namespace tsr::embree
