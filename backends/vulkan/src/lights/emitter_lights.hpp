#pragma once
// Emissive geometry as light for the rasterizer: each emissive mesh is cut
// into a few patches (up to eight, by octant of its bounds), and every patch
// of every emissive instance shines as a small area-like light. The path
// tracer samples the same triangles exactly; this keeps a scene lit only by
// emissive geometry (a Cornell box's ceiling panel) recognisably the same.
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace tsr::vk {

struct SceneState;

// Part of a mesh's surface, in the mesh's space. Only front faces
// (counter-clockwise) emit, so `vectorArea` (the sum of area x front normal)
// says how much of the patch faces one way: equal to `area` in length for a
// flat patch, near zero for a closed one.
struct EmitterPatch {
  glm::vec3 centre{0.0f};  // area-weighted
  glm::vec3 vectorArea{0.0f};
  float area = 0.0f;
};

// The patches of a triangle mesh. Meshes of few triangles are subdivided
// first, so a single quad still gives four patches.
std::vector<EmitterPatch> meshEmitterPatches(std::span<const glm::vec3> positions,
                                             std::span<const std::uint32_t> indices);

// A patch placed in the world and given its radiance. Its radiant intensity
// towards w is radiance * (directionalArea * max(0, dot(normal, w)) +
// (area - directionalArea) / 4): a flat Lambertian emitter when the two
// areas are equal, a uniformly glowing blob when directionalArea is 0.
struct EmitterLight {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  glm::vec3 radiance{0.0f};
  float area = 0.0f;
  float directionalArea = 0.0f;

  glm::vec3 power() const;  // radiant flux, for ranking
};

// The patches of every live instance with an emissive material (its emission
// colour; an emission texture is not averaged in). When there are more than
// `budget`, nearby patches are merged (grid clustering over the emitters'
// bounds, finer grids first) until at most `budget` remain; 0 gives none.
std::vector<EmitterLight> emitterLights(SceneState& scene, std::uint32_t budget);

// The light emitters leave bouncing around, as one constant, after Cohen
// et al.'s ambient term of progressive radiosity (1988): flux / (pi x area)
// x (R + R^2), over every live opaque instance's surface area with R their
// area-weighted reflectance (base colour luminance, at most 0.95). Cohen's
// full series R / (1 - R) holds for a closed room; scenes are open (a
// Cornell box has no front wall) and lose most light after two bounces, so
// the series stops there: builtin:cornell then agrees with the path tracer
// within the factor docs/rendering.md states.
glm::vec3 emitterAmbient(const SceneState& scene, const std::vector<EmitterLight>& lights);

// Surface area of a triangle mesh.
float meshArea(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices);

// Merges lights into at most `budget`, by clustering their positions.
std::vector<EmitterLight> clusterEmitters(std::vector<EmitterLight> lights, std::uint32_t budget);

}  // namespace tsr::vk
