#pragma once

#include "tsr/cov/vocabulary.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace tsr::cov {

// Static meshes get a high-quality acceleration structure; animated ones a
// refittable one, so a vertex update with unchanged topology only refits.
enum class MeshUsage { Static, Animated };

// Indexed triangles (or lines, or points, one pixel wide: an id renderer
// that cannot draw them refuses the mesh); an id pass needs nothing else.
struct MeshData {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;  // indicesPer(primitive) per primitive
  MeshUsage usage = MeshUsage::Static;
  Primitive primitive = Primitive::Triangles;

  // Throws Error without primitives, with an index count that is not a
  // multiple of indicesPer(primitive), an index out of range or a
  // non-finite position.
  void validate() const;
};

}  // namespace tsr::cov
