#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace tsr::cov {

// Static meshes get a high-quality acceleration structure; animated ones a
// refittable one, so a vertex update with unchanged topology only refits.
enum class MeshUsage { Static, Animated };

// Indexed triangles; an id pass needs nothing else.
struct MeshData {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;  // three per triangle
  MeshUsage usage = MeshUsage::Static;

  // Throws Error without triangles, with an index count that is not a
  // multiple of three, an index out of range or a non-finite position.
  void validate() const;
};

}  // namespace tsr::cov
