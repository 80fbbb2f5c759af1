#pragma once

#include "tsr/vk/vocabulary.hpp"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace tsr::vk {

// Indexed triangles (or lines, or points: unlit, one pixel wide). Without
// normals the shader uses the flat face normal; without uvs texture lookups
// read uv (0, 0).
struct MeshData {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;      // empty, or one per position
  std::vector<glm::vec2> uvs;          // empty, or one per position
  std::vector<std::uint32_t> indices;  // indicesPer(primitive) per primitive
  Primitive primitive = Primitive::Triangles;
};

}  // namespace tsr::vk
