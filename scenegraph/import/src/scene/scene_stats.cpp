#include "tsr/sg/import/scene_stats.hpp"

#include <functional>
#include <unordered_map>
#include <unordered_set>

#include "tsr/sg/scene.hpp"

namespace tsr::sg {
namespace {

// Visits every node reachable from root with its accumulated world matrix.
// Iterative, so deep hierarchies cannot exhaust the stack.
void walk(const Scene& scene, ContainerId root, const std::function<void(const Container&, const Mat4&)>& visit) {
  std::vector<std::pair<ContainerId, Mat4>> stack{{root, Mat4(1.0f)}};
  while (!stack.empty()) {
    auto [id, parent] = stack.back();
    stack.pop_back();
    const Container* c = scene.find(id);
    if (!c) continue;
    Mat4 world = parent;
    if (const auto* t = scene.find<Transform>(id)) world = parent * t->matrix();
    visit(*c, world);
    const std::vector<ContainerId>* children = nullptr;
    if (const auto* t = scene.find<Transform>(id)) children = &t->children();
    if (const auto* g = scene.find<Group>(id)) children = &g->children();
    if (children)
      for (auto it = children->rbegin(); it != children->rend(); ++it) stack.emplace_back(*it, world);
  }
}

void include(SceneStats& s, const Vec3& p) {
  if (!s.hasBounds) {
    s.boundsMin = s.boundsMax = p;
    s.hasBounds = true;
  } else {
    s.boundsMin = glm::min(s.boundsMin, p);
    s.boundsMax = glm::max(s.boundsMax, p);
  }
}

}  // namespace

SceneStats computeSceneStats(const Scene& scene, ContainerId root, std::uint64_t exactVertexLimit) {
  SceneStats s;
  for (ContainerId id : scene.ids()) {
    const Container* c = scene.find(id);
    ++s.containersByType[std::string(typeName(c->type()))];
    ++s.containers;
    if (c->type() == ContainerType::Light) ++s.lights;
    if (c->type() == ContainerType::Camera) ++s.cameras;
  }

  std::uint64_t instancedVertices = 0;
  std::unordered_set<ContainerId> unique;
  walk(scene, root, [&](const Container& c, const Mat4&) {
    if (c.type() == ContainerType::Light) ++s.lightInstances;
    if (c.type() != ContainerType::Geometry) return;
    const auto& g = static_cast<const Geometry&>(c);
    ++s.geometryInstances;
    s.triangles += g.triangleCount();
    instancedVertices += g.positions().size();
    if (!unique.insert(g.id()).second) return;
    s.uniqueTriangles += g.triangleCount();
    const auto* m = scene.find<SurfaceMaterial>(g.material());
    const auto* simple = scene.find<SimpleMaterial>(g.material());
    const Vec3 emitted = m ? m->emittedRadiance() : simple ? simple->emission() : Vec3(0.0f);
    // Lines and points light nothing, in either back-end.
    if (g.triangleCount() > 0 && (emitted.x > 0.0f || emitted.y > 0.0f || emitted.z > 0.0f)) ++s.emissiveGeometries;
  });

  const bool exact = instancedVertices <= exactVertexLimit;
  std::unordered_map<ContainerId, std::pair<Vec3, Vec3>> localBoxes;
  walk(scene, root, [&](const Container& c, const Mat4& world) {
    if (c.type() != ContainerType::Geometry) return;
    const auto& g = static_cast<const Geometry&>(c);
    if (g.positions().empty()) return;
    if (exact) {
      for (const Vec3& p : g.positions()) include(s, Vec3(world * Vec4(p, 1.0f)));
      return;
    }
    auto [it, fresh] = localBoxes.try_emplace(g.id(), g.positions().front(), g.positions().front());
    if (fresh)
      for (const Vec3& p : g.positions()) {
        it->second.first = glm::min(it->second.first, p);
        it->second.second = glm::max(it->second.second, p);
      }
    const auto& [lo, hi] = it->second;
    for (int k = 0; k < 8; ++k) {
      const Vec3 corner((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
      include(s, Vec3(world * Vec4(corner, 1.0f)));
    }
  });
  return s;
}

}  // namespace tsr::sg
