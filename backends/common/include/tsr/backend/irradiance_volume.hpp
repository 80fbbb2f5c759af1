#pragma once

#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tsr::backend {

// Light bounced off the scene, on a grid of probes: computed by a back-end
// that traces rays (the path tracer) for one that cannot (the rasterizer),
// after Majercik et al. 2019, "Dynamic Diffuse Global Illumination with
// Ray-Traced Irradiance Fields". Per probe:
//  - the irradiance on surfaces facing each of the six axis directions
//    (+x, -x, +y, -y, +z, -z: an "ambient cube"), W/m^2 per channel; a
//    surface facing n reads E(n) = sum_i n_i^2 E(the face n_i points to).
//    It holds everything a rasterizer does not light directly: light
//    bounced off surfaces and the environment, occluded; emitters seen
//    straight from the probe are left out (the rasterizer lights with
//    them). (Order-1 spherical harmonics, tried first, read a quarter too
//    little where light comes from one side, as a lit floor lights a
//    ceiling; order 2 cost the rasterizer's frame too much on lavapipe;
//    docs/raster-look.md.)
//  - per texel of an equal-area octahedral map of directions, the mean
//    distance to the first surface and its mean square, for Chebyshev's
//    visibility test (light does not leak through walls);
//  - a weight: 0 for a probe inside geometry (it saw back faces), 1 otherwise.
// Probes stand at the centres of the cells of the box [min, max] divided
// counts times per axis, x fastest.
struct IrradianceVolume {
  static constexpr std::uint32_t kFaces = 6;
  static constexpr std::uint32_t kDistanceSide = 8;  // texels per side of a probe's distance map
  static constexpr std::uint32_t kDistanceTexels = kDistanceSide * kDistanceSide;

  glm::vec3 min{0.0f}, max{0.0f};
  glm::uvec3 counts{0u};
  // kFaces per probe; rgb, and w of a probe's first face is its weight.
  std::vector<glm::vec4> irradiance;
  // kDistanceTexels per probe: mean distance and mean squared distance.
  std::vector<glm::vec2> distance;
  // Changes whenever a probe's values change (a reader re-uploads then).
  std::uint64_t version = 0;

  // A grid around the box [lo, hi] of at most max(maxProbes, 8) probes, its
  // cells as near to cubes as the box allows: the box grown by 5 % of its
  // largest side on every side (so a flat scene has room above and below
  // it), at least two probes per axis (so none lies in a plane the scene
  // is flat in). Values zero, weights 1.
  static IrradianceVolume over(const glm::vec3& lo, const glm::vec3& hi, std::uint32_t maxProbes);

  std::size_t probeCount() const { return std::size_t(counts.x) * counts.y * counts.z; }
  bool empty() const { return probeCount() == 0; }
  glm::vec3 cellSize() const { return (max - min) / glm::vec3(glm::max(counts, glm::uvec3(1u))); }
  glm::vec3 probePosition(std::size_t probe) const;
  float weight(std::size_t probe) const { return irradiance[probe * kFaces].w; }
  // The irradiance probe `probe` holds for surfaces facing n (unit).
  glm::vec3 irradianceAt(std::size_t probe, const glm::vec3& n) const;
};

// The cosine between d and each face's direction (faces in the volume's
// order), 0 for faces d is behind: how much a ray from d adds to each
// face's irradiance.
std::array<float, IrradianceVolume::kFaces> faceCosines(const glm::vec3& d);

// Clarberg's equal-area mapping between the unit square and the sphere
// (as pbrt-v4 has it): uniform points of the square are uniform
// directions, and the square's texels are equal solid angles.
glm::vec3 equalAreaSquareToSphere(const glm::vec2& p);
glm::vec2 equalAreaSphereToSquare(const glm::vec3& d);

}  // namespace tsr::backend
