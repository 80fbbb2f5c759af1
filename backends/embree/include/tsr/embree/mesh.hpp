#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace tsr::embree {

// Static meshes get a high-quality BVH; animated ones a refittable one, so a
// vertex update with unchanged topology only refits.
enum class MeshUsage { Static, Animated };

struct MeshData {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;      // empty, or one per position
  std::vector<glm::vec2> uvs;          // empty, or one per position
  std::vector<std::uint32_t> indices;  // three per triangle
  MeshUsage usage = MeshUsage::Static;
};

}  // namespace tsr::embree
