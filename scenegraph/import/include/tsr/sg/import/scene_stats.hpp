#pragma once
// Numbers about a scene graph as it would render: containers by type,
// triangles per instance and unique, world-space bounds. Walks the graph
// from a root, accumulating Transform matrices.
#include <cstdint>
#include <map>
#include <string>

#include "tsr/sg/types.hpp"

namespace tsr::sg {

class Scene;

struct SceneStats {
  std::map<std::string, std::size_t> containersByType;  // every container in the scene
  std::size_t containers = 0;
  std::uint64_t geometryInstances = 0;  // Geometry reached along each path from the root
  std::uint64_t triangles = 0;          // counted per instance
  std::uint64_t uniqueTriangles = 0;    // counted once per reachable Geometry
  std::uint64_t lightInstances = 0;
  std::size_t lights = 0;  // Light containers
  std::size_t cameras = 0;
  std::size_t emissiveGeometries = 0;  // reachable Geometry whose SurfaceMaterial emits
  bool hasBounds = false;              // false when no vertex is reachable
  Vec3 boundsMin{0.0f};
  Vec3 boundsMax{0.0f};
};

// Bounds are exact (every instanced vertex transformed) unless the scene
// instances more than `exactVertexLimit` vertices, then per instance the
// local box's corners are transformed (conservative).
SceneStats computeSceneStats(const Scene& scene, ContainerId root, std::uint64_t exactVertexLimit = 50'000'000);

}  // namespace tsr::sg
