#pragma once
// The mesh elements photons are counted on (Weber et al. 2004 §4; DEPT's
// buckets): every triangle of an instance's mesh split uniformly into n^2
// sub-triangles, n per mesh from the longest edge and the element size.
// Elements exist only for the photon pass and the irradiance lookup; the
// render meshes are untouched. Grid points are welded by position within an
// instance, so elements that touch share corners (ring neighbourhoods and
// continuous interpolation need that). Private to the back-end.
#include "scene/scene_state.hpp"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>
#include <vector>

namespace tsr::embree {

inline constexpr std::uint32_t kNoElement = std::numeric_limits<std::uint32_t>::max();

struct ElementInstance {
  bool present = false;
  std::uint32_t mesh = 0;       // mesh index the elements were built from
  std::uint32_t triangles = 0;  // of that mesh, to detect topology changes
  std::uint32_t level = 1;      // n: n^2 elements per triangle
  std::uint32_t firstElement = 0;
};

struct ElementSet {
  std::vector<ElementInstance> instances;  // indexed like SceneState::views
  std::vector<std::uint32_t> corners;      // 3 welded vertex ids per element
  std::vector<std::uint32_t> elementInstance;
  // Per welded vertex: where it sits, to recompute positions every frame
  // (instances move, animated meshes deform).
  std::vector<std::uint32_t> vertexInstance;
  std::vector<std::uint32_t> vertexPrim;
  std::vector<glm::vec2> vertexBary;
  // Vertex -> elements touching it (CSR).
  std::vector<std::uint32_t> vertexStart;
  std::vector<std::uint32_t> vertexElements;

  std::size_t elementCount() const { return elementInstance.size(); }
  std::size_t vertexCount() const { return vertexPrim.size(); }

  // The element holding barycentrics (b1, b2) of triangle prim, and the
  // point's barycentrics over that element's three corners.
  std::uint32_t locate(std::uint32_t instance, std::uint32_t prim, float b1, float b2, glm::vec3* weights) const;
  // Whether the scene still has the instances and topology these were built for.
  bool matches(const SceneState& scene) const;
};

// elementSize in world units (at the current pose); at most maxElements in
// all (levels shrink evenly until they fit).
ElementSet buildElements(const SceneState& scene, float elementSize, std::uint32_t maxElements);

// Element geometry at the scene's current pose.
struct ElementGeometry {
  std::vector<glm::vec3> centroid;
  std::vector<glm::vec3> normal;  // unit, from the winding
  std::vector<float> area;
  glm::vec3 lower{0.0f}, upper{0.0f};  // world bounds of all elements
};
ElementGeometry elementGeometry(const ElementSet& elements, const SceneState& scene);

}  // namespace tsr::embree
