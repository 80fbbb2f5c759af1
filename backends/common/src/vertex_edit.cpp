#include "tsr/backend/vertex_edit.hpp"

namespace tsr::backend {

std::optional<std::string> VertexEdit::invalidReason(std::size_t vertexCount) const {
  if (positions.size() != vertexCount)
    return "vertex edit carries " + std::to_string(positions.size()) + " positions for a mesh of " +
           std::to_string(vertexCount) + " vertices";
  if (std::uint64_t{first} + count > positions.size())
    return "vertex range [" + std::to_string(first) + ", " + std::to_string(std::uint64_t{first} + count) +
           ") exceeds the mesh's " + std::to_string(positions.size()) + " vertices";
  if (!normals.empty() && normals.size() != positions.size())
    return "vertex edit carries " + std::to_string(normals.size()) + " normals for " +
           std::to_string(positions.size()) + " positions";
  return std::nullopt;
}

}  // namespace tsr::backend
