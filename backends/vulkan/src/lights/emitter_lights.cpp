#include "lights/emitter_lights.hpp"

#include "scene/scene_state.hpp"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

namespace tsr::vk {

namespace {

constexpr float kPi = 3.14159265358979f;

// Below this many triangles a mesh is subdivided (each triangle into 16), so
// that its octants hold parts of it: a two-triangle quad gives four patches.
constexpr std::size_t kSubdivideBelow = 16;
constexpr int kSubdivisions = 4;

float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

}  // namespace

glm::vec3 EmitterLight::power() const { return kPi * radiance * area; }

std::vector<EmitterPatch> meshEmitterPatches(std::span<const glm::vec3> positions,
                                             std::span<const std::uint32_t> indices) {
  if (positions.empty() || indices.size() < 3) return {};
  glm::vec3 lo = positions[0], hi = positions[0];
  for (const glm::vec3& p : positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const glm::vec3 mid = 0.5f * (lo + hi), extent = hi - lo;
  const float largest = std::max({extent.x, extent.y, extent.z});
  // A flat mesh is split in its plane only.
  const glm::bvec3 split(extent.x > 1e-4f * largest, extent.y > 1e-4f * largest, extent.z > 1e-4f * largest);
  struct Bin {
    glm::vec3 weightedCentre{0.0f}, vectorArea{0.0f};
    float area = 0.0f;
  };
  std::array<Bin, 8> bins{};
  auto add = [&](const glm::vec3& centre, const glm::vec3& vectorArea, float area) {
    const int bin = (split.x && centre.x > mid.x ? 1 : 0) | (split.y && centre.y > mid.y ? 2 : 0) |
                    (split.z && centre.z > mid.z ? 4 : 0);
    bins[bin].weightedCentre += centre * area;
    bins[bin].vectorArea += vectorArea;
    bins[bin].area += area;
  };
  const std::size_t triangles = indices.size() / 3;
  const int n = triangles < kSubdivideBelow ? kSubdivisions : 1;
  const float part = 1.0f / float(n * n);
  for (std::size_t t = 0; t < triangles; ++t) {
    const glm::vec3 a = positions[indices[3 * t]], b = positions[indices[3 * t + 1]], c = positions[indices[3 * t + 2]];
    const glm::vec3 vectorArea = 0.5f * glm::cross(b - a, c - a);
    const float area = glm::length(vectorArea);
    if (!(area > 0.0f)) continue;
    // The n x n barycentric grid: sub-triangles pointing up and down, all of
    // area / n^2, identified by their centroids.
    auto at = [&](float i, float j) { return a + (b - a) * (i / float(n)) + (c - a) * (j / float(n)); };
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        add(at(float(i) + 1.0f / 3.0f, float(j) + 1.0f / 3.0f), vectorArea * part, area * part);
        if (i + j <= n - 2) add(at(float(i) + 2.0f / 3.0f, float(j) + 2.0f / 3.0f), vectorArea * part, area * part);
      }
  }
  std::vector<EmitterPatch> patches;
  for (const Bin& b : bins)
    if (b.area > 0.0f) patches.push_back({b.weightedCentre / b.area, b.vectorArea, b.area});
  return patches;
}

std::vector<EmitterLight> clusterEmitters(std::vector<EmitterLight> lights, std::uint32_t budget) {
  if (budget == 0) return {};
  if (lights.size() <= budget) return lights;
  glm::vec3 lo = lights[0].position, hi = lo;
  for (const EmitterLight& l : lights) {
    lo = glm::min(lo, l.position);
    hi = glm::max(hi, l.position);
  }
  const glm::vec3 extent = glm::max(hi - lo, glm::vec3(1e-20f));
  // The finest grid whose occupied cells fit the budget (one cell always does).
  std::unordered_map<std::uint32_t, std::uint32_t> cellOf;
  std::vector<std::uint32_t> clusterOf(lights.size());
  std::uint32_t clusters = 0;
  for (std::uint32_t g = 64; g >= 1; g /= 2) {
    cellOf.clear();
    for (std::size_t i = 0; i < lights.size(); ++i) {
      const glm::vec3 f = (lights[i].position - lo) / extent * float(g);
      const glm::uvec3 c = glm::min(glm::uvec3(glm::max(f, glm::vec3(0.0f))), glm::uvec3(g - 1));
      const std::uint32_t key = (c.z * g + c.y) * g + c.x;
      clusterOf[i] = cellOf.emplace(key, std::uint32_t(cellOf.size())).first->second;
    }
    clusters = std::uint32_t(cellOf.size());
    if (clusters <= budget) break;
  }
  // Sums: flux-weighted positions, area-weighted radiance, vector areas.
  struct Sum {
    glm::vec3 position{0.0f}, radiance{0.0f}, vectorArea{0.0f};
    float weight = 0.0f, area = 0.0f;
  };
  std::vector<Sum> sums(clusters);
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const EmitterLight& l = lights[i];
    Sum& s = sums[clusterOf[i]];
    const float w = std::max(luminance(l.radiance) * l.area, 1e-30f);
    s.position += l.position * w;
    s.weight += w;
    s.radiance += l.radiance * l.area;
    s.area += l.area;
    s.vectorArea += l.normal * l.directionalArea;
  }
  std::vector<EmitterLight> merged;
  for (const Sum& s : sums) {
    if (!(s.area > 0.0f)) continue;
    EmitterLight m;
    m.position = s.position / s.weight;
    m.radiance = s.radiance / s.area;
    m.area = s.area;
    const float directional = glm::length(s.vectorArea);
    m.directionalArea = std::min(directional, s.area);
    if (directional > 0.0f) m.normal = s.vectorArea / directional;
    merged.push_back(m);
  }
  return merged;
}

float meshArea(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices) {
  double area = 0.0;
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const glm::vec3 a = positions[indices[t]], b = positions[indices[t + 1]], c = positions[indices[t + 2]];
    area += 0.5 * double(glm::length(glm::cross(b - a, c - a)));
  }
  return float(area);
}

glm::vec3 emitterAmbient(const SceneState& s, const std::vector<EmitterLight>& lights) {
  glm::vec3 flux(0.0f);
  for (const EmitterLight& l : lights) flux += l.power();
  if (flux == glm::vec3(0.0f)) return flux;
  double area = 0.0, reflecting = 0.0;
  for (const InstanceRecord& inst : s.instances) {
    if (!inst.alive) continue;
    const Material& m = s.materials[inst.material].material;
    if (m.isTransparent()) continue;
    // Uniform scale's effect on area; shears and stretches only roughly.
    const double a = double(s.meshes[inst.mesh].area) *
                     std::pow(std::abs(double(glm::determinant(glm::mat3(inst.transform)))), 2.0 / 3.0);
    area += a;
    reflecting += a * std::clamp(double(luminance(m.baseColor)), 0.0, 0.95);
  }
  if (!(area > 0.0)) return glm::vec3(0.0f);
  const double r = std::min(reflecting / area, 0.95);
  return flux * float((r + r * r) / (double(kPi) * area));
}

std::vector<EmitterLight> emitterLights(SceneState& s, std::uint32_t budget) {
  std::vector<EmitterLight> lights;
  if (budget == 0) return lights;
  for (const InstanceRecord& inst : s.instances) {
    if (!inst.alive) continue;
    const Material& material = s.materials[inst.material].material;
    if (!material.isEmissive()) continue;
    MeshRecord& mesh = s.meshes[inst.mesh];
    if (mesh.primitive != Primitive::Triangles) continue;  // a line or point lights nothing
    if (mesh.patchesDirty) {
      mesh.patches = meshEmitterPatches(s.geometry->positions(mesh.span, mesh.vertexCount),
                                        s.geometry->indices(mesh.span, mesh.indexCount));
      mesh.patchesDirty = false;
    }
    const glm::mat3 linear(inst.transform);
    const float det = glm::determinant(linear);
    if (!(std::abs(det) > 0.0f)) continue;
    // Areas transform by the cofactor matrix (cross(Mu, Mv) = cof(M) cross(u, v)).
    const glm::mat3 cofactor = glm::transpose(glm::inverse(linear)) * det;
    for (const EmitterPatch& p : mesh.patches) {
      EmitterLight l;
      l.position = glm::vec3(inst.transform * glm::vec4(p.centre, 1.0f));
      const glm::vec3 vectorArea = cofactor * p.vectorArea;
      const float directional = glm::length(vectorArea), local = glm::length(p.vectorArea);
      l.area = local > 0.0f ? p.area * directional / local : p.area * std::pow(std::abs(det), 2.0f / 3.0f);
      l.directionalArea = std::min(directional, l.area);
      if (directional > 0.0f) l.normal = vectorArea / directional;
      l.radiance = material.emission;
      if (l.area > 0.0f && std::isfinite(l.area)) lights.push_back(l);
    }
  }
  lights = clusterEmitters(std::move(lights), budget);
  // The brightest first: they get the shadow maps there are.
  std::stable_sort(lights.begin(), lights.end(), [](const EmitterLight& a, const EmitterLight& b) {
    return luminance(a.power()) > luminance(b.power());
  });
  return lights;
}

}  // namespace tsr::vk
