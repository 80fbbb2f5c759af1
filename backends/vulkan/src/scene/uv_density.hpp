#pragma once
// A mesh's mean uv units a length unit of its positions: the square root
// of its triangles' total uv area over their total area. The shaders' level
// of detail for textures (shaders/slot_texture.glsl) takes a pixel's size on
// the surface times this, so a mesh whose uvs stretch unevenly (an atlas)
// is filtered at its mean density. Zero without uvs or area. Made when a
// mesh is added; vertex edits keep it (a deforming mesh's density changes
// little, and a pass over every triangle each edit would cost more).
#include <cmath>
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

namespace tsr::vk {

inline float uvDensity(std::span<const glm::vec3> positions, std::span<const glm::vec2> uvs,
                       std::span<const std::uint32_t> indices) {
  if (uvs.size() != positions.size()) return 0.0f;
  double area = 0.0, uvArea = 0.0;
  for (std::size_t i = 0; i + 2 < indices.size(); i += 3) {
    const std::uint32_t a = indices[i], b = indices[i + 1], c = indices[i + 2];
    if (a >= positions.size() || b >= positions.size() || c >= positions.size()) continue;
    area += glm::length(glm::cross(positions[b] - positions[a], positions[c] - positions[a]));
    const glm::vec2 du = uvs[b] - uvs[a], dv = uvs[c] - uvs[a];
    uvArea += std::abs(du.x * dv.y - du.y * dv.x);
  }
  return area > 0.0 ? float(std::sqrt(uvArea / area)) : 0.0f;
}

}  // namespace tsr::vk
