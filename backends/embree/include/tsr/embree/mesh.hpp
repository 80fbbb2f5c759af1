#pragma once

#include "tsr/backend/shared_elements.hpp"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>

namespace tsr::embree {

// Static meshes get a high-quality BVH; animated ones a refittable one, so a
// vertex update with unchanged topology only refits.
enum class MeshUsage { Static, Animated };

// A mesh's arrays, the caller's own or shared with it (a scene replica's,
// held without a copy; an edit by range copies them first).
struct MeshData {
  backend::SharedElements<glm::vec3> positions;
  backend::SharedElements<glm::vec3> normals;      // empty, or one per position
  backend::SharedElements<glm::vec2> uvs;          // empty, or one per position
  backend::SharedElements<std::uint32_t> indices;  // three per triangle
  MeshUsage usage = MeshUsage::Static;
};

}  // namespace tsr::embree
