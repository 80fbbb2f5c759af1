#include "photons/photon_elements.hpp"

#include "tsr/embree/rng.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace tsr::embree {

namespace {

// Sub-triangle numbering for level n: the n(n+1)/2 upward triangles (i, j)
// row by row, then the n(n-1)/2 downward ones.
std::uint32_t upIndex(std::uint32_t n, std::uint32_t i, std::uint32_t j) { return j * n - j * (j - 1) / 2 + i; }
std::uint32_t downIndex(std::uint32_t n, std::uint32_t i, std::uint32_t j) {
  return n * (n + 1) / 2 + j * (n - 1) - j * (j - 1) / 2 + i;
}

glm::vec3 objectPoint(const MeshData& m, std::uint32_t prim, const glm::vec2& b) {
  const std::uint32_t* idx = &m.indices[3 * std::size_t(prim)];
  return (1.0f - b.x - b.y) * m.positions[idx[0]] + b.x * m.positions[idx[1]] + b.y * m.positions[idx[2]];
}

struct KeyHash {
  std::size_t operator()(const glm::ivec3& k) const {
    return std::size_t(splitmix64((std::uint64_t(std::uint32_t(k.x)) << 32) ^ std::uint32_t(k.y)) ^
                       std::uint32_t(k.z) * 0x9E3779B97F4A7C15ull);
  }
};

}  // namespace

std::uint32_t ElementSet::locate(std::uint32_t instance, std::uint32_t prim, float b1, float b2,
                                 glm::vec3* weights) const {
  if (instance >= instances.size() || !instances[instance].present) return kNoElement;
  const ElementInstance& in = instances[instance];
  if (prim >= in.triangles) return kNoElement;
  const std::uint32_t n = in.level;
  const float x = std::clamp(b1, 0.0f, 1.0f) * float(n), y = std::clamp(b2, 0.0f, 1.0f) * float(n);
  const std::uint32_t i = std::min(std::uint32_t(x), n - 1);
  const std::uint32_t j = std::min(std::uint32_t(y), n - 1 - i);
  const float fx = std::clamp(x - float(i), 0.0f, 1.0f), fy = std::clamp(y - float(j), 0.0f, 1.0f);
  const bool down = fx + fy > 1.0f && i + j + 2 <= n;
  glm::vec3 w = down ? glm::vec3(1.0f - fy, fx + fy - 1.0f, 1.0f - fx) : glm::vec3(1.0f - fx - fy, fx, fy);
  w = glm::max(w, glm::vec3(0.0f));
  w /= std::max(1e-20f, w.x + w.y + w.z);
  if (weights) *weights = w;
  return in.firstElement + prim * n * n + (down ? downIndex(n, i, j) : upIndex(n, i, j));
}

bool ElementSet::matches(const SceneState& scene) const {
  if (scene.views.size() != instances.size()) return false;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const bool present = scene.instances[i] && scene.views[i].mesh;
    if (present != instances[i].present) return false;
    if (!present) continue;
    if (index(scene.instances[i]->mesh) != instances[i].mesh ||
        scene.views[i].mesh->indices.size() / 3 != instances[i].triangles)
      return false;
  }
  return true;
}

ElementSet buildElements(const SceneState& scene, float elementSize, std::uint32_t maxElements) {
  ElementSet set;
  set.instances.assign(scene.views.size(), {});
  // Level per instance from its longest world-space edge.
  std::uint64_t total = 0;
  for (std::size_t i = 0; i < scene.views.size(); ++i) {
    const InstanceView& v = scene.views[i];
    if (!scene.instances[i] || !v.mesh) continue;
    ElementInstance& in = set.instances[i];
    in.present = true;
    in.mesh = index(scene.instances[i]->mesh);
    in.triangles = std::uint32_t(v.mesh->indices.size() / 3);
    float longest = 0.0f;
    for (std::size_t t = 0; t < v.mesh->indices.size(); t += 3) {
      glm::vec3 p[3];
      for (int k = 0; k < 3; ++k)
        p[k] = glm::vec3(v.transform * glm::vec4(v.mesh->positions[v.mesh->indices[t + k]], 1.0f));
      for (int k = 0; k < 3; ++k) longest = std::max(longest, glm::length(p[k] - p[(k + 1) % 3]));
    }
    const float levels = elementSize > 0.0f ? std::ceil(longest / elementSize) : 1.0f;
    in.level = std::uint32_t(std::clamp(std::isfinite(levels) ? levels : 1.0f, 1.0f, 4096.0f));
    total += std::uint64_t(in.triangles) * in.level * in.level;
  }
  if (total > maxElements) {
    const float s = std::sqrt(float(maxElements) / float(total));
    for (ElementInstance& in : set.instances) in.level = std::max(1u, std::uint32_t(float(in.level) * s));
  }

  for (std::size_t i = 0; i < set.instances.size(); ++i) {
    ElementInstance& in = set.instances[i];
    if (!in.present) continue;
    const MeshData& m = *scene.views[i].mesh;
    const std::uint32_t n = in.level;
    in.firstElement = std::uint32_t(set.elementInstance.size());
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const glm::vec3& p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const float quantum = std::max(1e-30f, 1e-5f * glm::length(hi - lo));
    std::unordered_map<glm::ivec3, std::uint32_t, KeyHash> welded;
    std::vector<std::uint32_t> grid((n + 1) * (n + 2) / 2);
    for (std::uint32_t t = 0; t < in.triangles; ++t) {
      // Grid point (a, b) of this triangle -> welded vertex id.
      for (std::uint32_t b = 0, g = 0; b <= n; ++b) {
        for (std::uint32_t a = 0; a + b <= n; ++a, ++g) {
          const glm::vec2 bary(float(a) / float(n), float(b) / float(n));
          const glm::vec3 p = objectPoint(m, t, bary);
          const glm::ivec3 key(glm::round(p / quantum));
          auto [it, added] = welded.try_emplace(key, std::uint32_t(set.vertexPrim.size()));
          if (added) {
            set.vertexInstance.push_back(std::uint32_t(i));
            set.vertexPrim.push_back(t);
            set.vertexBary.push_back(bary);
          }
          grid[g] = it->second;
        }
      }
      auto at = [&](std::uint32_t a, std::uint32_t b) { return grid[b * (n + 1) - b * (b - 1) / 2 + a]; };
      const std::size_t base = set.elementInstance.size();
      set.elementInstance.resize(base + n * n, std::uint32_t(i));
      set.corners.resize(3 * (base + n * n));
      for (std::uint32_t j = 0; j < n; ++j) {
        for (std::uint32_t a = 0; a + j < n; ++a) {
          std::uint32_t* c = &set.corners[3 * (base + upIndex(n, a, j))];
          c[0] = at(a, j), c[1] = at(a + 1, j), c[2] = at(a, j + 1);
          if (a + j + 2 <= n) {
            std::uint32_t* d = &set.corners[3 * (base + downIndex(n, a, j))];
            d[0] = at(a + 1, j), d[1] = at(a + 1, j + 1), d[2] = at(a, j + 1);
          }
        }
      }
    }
  }

  set.vertexStart.assign(set.vertexCount() + 1, 0);
  for (std::uint32_t v : set.corners) ++set.vertexStart[v + 1];
  for (std::size_t v = 0; v < set.vertexCount(); ++v) set.vertexStart[v + 1] += set.vertexStart[v];
  set.vertexElements.resize(set.corners.size());
  std::vector<std::uint32_t> fill(set.vertexStart.begin(), set.vertexStart.end() - 1);
  for (std::size_t k = 0; k < set.corners.size(); ++k)
    set.vertexElements[fill[set.corners[k]]++] = std::uint32_t(k / 3);
  return set;
}

ElementGeometry elementGeometry(const ElementSet& set, const SceneState& scene) {
  std::vector<glm::vec3> world(set.vertexCount());
  for (std::size_t v = 0; v < world.size(); ++v) {
    const InstanceView& view = scene.views[set.vertexInstance[v]];
    world[v] =
        glm::vec3(view.transform * glm::vec4(objectPoint(*view.mesh, set.vertexPrim[v], set.vertexBary[v]), 1.0f));
  }
  ElementGeometry g;
  const std::size_t n = set.elementCount();
  g.centroid.resize(n);
  g.normal.resize(n);
  g.area.resize(n);
  g.lower = glm::vec3(std::numeric_limits<float>::max());
  g.upper = -g.lower;
  for (const glm::vec3& p : world) g.lower = glm::min(g.lower, p), g.upper = glm::max(g.upper, p);
  for (std::size_t e = 0; e < n; ++e) {
    const glm::vec3 &a = world[set.corners[3 * e]], &b = world[set.corners[3 * e + 1]],
                    &c = world[set.corners[3 * e + 2]];
    const glm::vec3 cr = glm::cross(b - a, c - a);
    const float len = glm::length(cr);
    g.centroid[e] = (a + b + c) / 3.0f;
    g.area[e] = 0.5f * len;
    g.normal[e] = len > 0.0f ? cr / len : glm::vec3(0.0f);
  }
  if (world.empty()) g.lower = g.upper = glm::vec3(0.0f);
  return g;
}

}  // namespace tsr::embree
