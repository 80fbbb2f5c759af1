#pragma once
// A ranged vertex edit as every back-end takes it: the mesh's whole arrays
// after the edit and the range that changed. A back-end copies the range;
// one that derives something from all vertices (the rasterizer's
// quantization box) derives it again from the exact arrays, so an edited
// mesh is held exactly as a new mesh of the same arrays would be, whatever
// edits came before.
#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace tsr::backend {

struct VertexEdit {
  std::span<const glm::vec3> positions = {};  // all of the mesh's positions
  std::span<const glm::vec3> normals = {};    // all of its normals when they changed too, else empty
  std::uint32_t first = 0;                    // the changed range [first, first + count)
  std::uint32_t count = 0;

  std::span<const glm::vec3> changedPositions() const { return positions.subspan(first, count); }
  std::span<const glm::vec3> changedNormals() const {
    return normals.empty() ? normals : normals.subspan(first, count);
  }
  // Why no back-end can apply it to a mesh of `vertexCount` vertices (arrays
  // of another size, a range beyond them), or nothing; see validate.hpp.
  std::optional<std::string> invalidReason(std::size_t vertexCount) const;
};

}  // namespace tsr::backend
