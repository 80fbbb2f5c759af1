#include "tsr/cov/mesh.hpp"

#include "tsr/cov/error.hpp"

#include <cmath>
#include <string>

namespace tsr::cov {

void MeshData::validate() const {
  if (indices.empty()) throw Error("mesh has nothing to draw");
  const std::size_t per = indicesPer(primitive);
  if (indices.size() % per != 0)
    throw Error("mesh index count " + std::to_string(indices.size()) + " is not a multiple of " + std::to_string(per));
  for (std::uint32_t i : indices)
    if (i >= positions.size())
      throw Error("mesh index " + std::to_string(i) + " exceeds its " + std::to_string(positions.size()) + " vertices");
  for (const auto& p : positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw Error("mesh position contains NaN or infinity");
}

}  // namespace tsr::cov
