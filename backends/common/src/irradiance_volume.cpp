#include "tsr/backend/irradiance_volume.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace tsr::backend {

namespace {
constexpr float kPi = 3.14159265358979323846f;
}

IrradianceVolume IrradianceVolume::over(const glm::vec3& lo, const glm::vec3& hi, std::uint32_t maxProbes) {
  const glm::vec3 box = glm::max(hi - lo, glm::vec3(0.0f));
  const float margin = std::max(0.05f * std::max({box.x, box.y, box.z}), 1e-4f);
  IrradianceVolume v;
  v.min = lo - margin;
  v.max = glm::max(hi, lo) + margin;
  const glm::vec3 extent = v.max - v.min;
  maxProbes = std::max(maxProbes, 8u);
  // The smallest cell that keeps the count within maxProbes: from the cube
  // root of the volume per probe, grown until the grid fits.
  float cell = std::cbrt(extent.x * extent.y * extent.z / float(maxProbes));
  for (int attempt = 0; attempt < 256; ++attempt) {
    for (int a = 0; a < 3; ++a) v.counts[a] = std::max(2u, std::uint32_t(std::lround(extent[a] / cell)));
    if (v.probeCount() <= maxProbes) break;
    cell *= 1.05f;
  }
  v.irradiance.assign(v.probeCount() * kFaces, glm::vec4(0.0f));
  for (std::size_t p = 0; p < v.probeCount(); ++p) v.irradiance[p * kFaces].w = 1.0f;
  v.distance.assign(v.probeCount() * kDistanceTexels, glm::vec2(0.0f));
  return v;
}

glm::vec3 IrradianceVolume::probePosition(std::size_t probe) const {
  const glm::uvec3 c(std::uint32_t(probe % counts.x), std::uint32_t(probe / counts.x % counts.y),
                     std::uint32_t(probe / (std::size_t(counts.x) * counts.y)));
  return min + (glm::vec3(c) + 0.5f) * cellSize();
}

glm::vec3 IrradianceVolume::irradianceAt(std::size_t probe, const glm::vec3& n) const {
  const glm::vec4* face = &irradiance[probe * kFaces];
  const glm::vec3 n2 = n * n;
  return n2.x * glm::vec3(face[n.x < 0.0f ? 1 : 0]) + n2.y * glm::vec3(face[n.y < 0.0f ? 3 : 2]) +
         n2.z * glm::vec3(face[n.z < 0.0f ? 5 : 4]);
}

std::array<float, IrradianceVolume::kFaces> faceCosines(const glm::vec3& d) {
  return {std::max(d.x, 0.0f),  std::max(-d.x, 0.0f), std::max(d.y, 0.0f),
          std::max(-d.y, 0.0f), std::max(d.z, 0.0f),  std::max(-d.z, 0.0f)};
}

glm::vec3 equalAreaSquareToSphere(const glm::vec2& p) {
  const float u = 2.0f * p.x - 1.0f, v = 2.0f * p.y - 1.0f;
  const float au = std::abs(u), av = std::abs(v);
  // The distance from the square's inner diamond says how far from the
  // pole the direction lies; the position along it, the azimuth.
  const float signedDistance = 1.0f - (au + av);
  const float r = 1.0f - std::abs(signedDistance);
  const float phi = (r == 0.0f ? 1.0f : (av - au) / r + 1.0f) * kPi / 4.0f;
  const float z = std::copysign(1.0f - r * r, signedDistance);
  const float s = r * std::sqrt(std::max(0.0f, 2.0f - r * r));
  return {std::copysign(std::cos(phi), u) * s, std::copysign(std::sin(phi), v) * s, z};
}

glm::vec2 equalAreaSphereToSquare(const glm::vec3& d) {
  const float x = std::abs(d.x), y = std::abs(d.y), z = std::abs(d.z);
  const float r = std::sqrt(std::max(0.0f, 1.0f - z));
  const float a = std::max(x, y);
  const float b = a == 0.0f ? 0.0f : std::min(x, y) / a;
  float phi = std::atan(b) * 2.0f / kPi;
  if (x < y) phi = 1.0f - phi;
  float v = phi * r, u = r - v;
  if (d.z < 0.0f) {  // the southern hemisphere folds out over the diamond's edges
    std::swap(u, v);
    u = 1.0f - u;
    v = 1.0f - v;
  }
  return {0.5f * (std::copysign(u, d.x) + 1.0f), 0.5f * (std::copysign(v, d.y) + 1.0f)};
}

}  // namespace tsr::backend
