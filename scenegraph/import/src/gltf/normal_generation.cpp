#include "gltf/normal_generation.hpp"

#include <cmath>

namespace tsr::sg {
namespace {

// Degenerate triangles and isolated vertices get +Z rather than NaN, which
// the scene graph would refuse.
Vec3 safeNormalize(const Vec3& v) {
  const float len = std::sqrt(glm::dot(v, v));
  return len > 0.0f && std::isfinite(len) ? v / len : Vec3(0.0f, 0.0f, 1.0f);
}

}  // namespace

void generateSmoothNormals(parsed::Primitive& p) {
  std::vector<Vec3> sum(p.positions.size(), Vec3(0.0f));
  for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) {
    const std::uint32_t a = p.indices[t], b = p.indices[t + 1], c = p.indices[t + 2];
    // Unnormalized: the cross product's length weights by area.
    const Vec3 n = glm::cross(p.positions[b] - p.positions[a], p.positions[c] - p.positions[a]);
    if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) continue;
    sum[a] += n;
    sum[b] += n;
    sum[c] += n;
  }
  p.normals.resize(sum.size());
  for (std::size_t i = 0; i < sum.size(); ++i) p.normals[i] = safeNormalize(sum[i]);
}

}  // namespace tsr::sg
