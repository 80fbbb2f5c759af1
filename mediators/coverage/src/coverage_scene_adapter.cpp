#include "coverage_scene_adapter.hpp"

#include <limits>

#include <spdlog/spdlog.h>

#include "translation.hpp"
#include "tsr/cov/error.hpp"

namespace tsr::med::coverage_mediator {

namespace {
bool isNode(sg::ContainerType t) { return (sg::typeBit(t) & sg::kNodeTypes) != 0; }
bool isMaterial(sg::ContainerType t) { return (sg::typeBit(t) & sg::kMaterialTypes) != 0; }

// The id pass needs positions and topology only; normals, uvs and colours
// are ignored.
const sg::FieldMask kShapeFields = sg::fieldBit(sg::Geometry::Positions) | sg::fieldBit(sg::Geometry::Indices) |
                                   sg::fieldBit(sg::Geometry::Motion);
}  // namespace

CoverageSceneAdapter::CoverageSceneAdapter(RendererFactory make, sg::ContainerId root)
    : make_(std::move(make)), root_(root) {}

void CoverageSceneAdapter::convert(const sg::Scene& scene) {
  renderer_ = make_();
  meshes_.clear();
  unrenderable_.clear();
  instances_.clear();
  place(scene);
}

void CoverageSceneAdapter::sync(const sg::Scene& scene, const sg::MergedChanges& changes) {
  // Phase 0: does the shape of the graph change? Then placement is redone
  // (a diff: surviving instances keep their back-end objects).
  bool structural = false;
  bool geometryGone = false;
  for (const auto& [id, e] : changes.entries()) {
    if (e.destroyed && e.type == sg::ContainerType::Geometry) geometryGone = true;
    if (!isNode(e.type)) continue;
    if (e.created || e.destroyed) structural = true;
    if (sg::isParentType(e.type) && e.changed(sg::Group::Children)) structural = true;
  }
  // Phase 1: meshes, in place where the geometry stays renderable.
  if (syncMeshes(scene, changes)) structural = true;
  // Phase 2: instances, either re-placed as a whole or moved one by one.
  if (structural)
    place(scene);
  else
    syncTransforms(scene, changes);
  // Phase 3: transparency of the instances whose material changed.
  syncTransparency(scene, changes);
  if (structural || geometryGone) dropUnusedMeshes(scene);
}

bool CoverageSceneAdapter::syncMeshes(const sg::Scene& scene, const sg::MergedChanges& changes) {
  using G = sg::Geometry;
  std::unordered_set<sg::ContainerId> flipped;  // became renderable or stopped being so
  for (const auto& [id, e] : changes.entries()) {
    if (e.type != sg::ContainerType::Geometry || e.created || e.destroyed || !(e.mask & kShapeFields)) continue;
    auto held = meshes_.find(id);
    const bool wasSkipped = unrenderable_.count(id) != 0;
    if (held == meshes_.end() && !wasSkipped) continue;  // not instanced here
    const auto* g = scene.find<G>(id);
    const bool renderable = !g->invalidReason() && g->triangleCount() > 0;
    if (held == meshes_.end() || !renderable) {
      flipped.insert(id);
      continue;
    }
    // Position edits by range keep the topology: update those ranges only.
    const auto* pos = e.rangedEdit(G::Positions);
    try {
      if ((e.mask & kShapeFields) == sg::fieldBit(G::Positions) && pos) {
        for (const auto& r : pos->ranges) {
          std::span<const glm::vec3> p(g->positions().data() + r.begin, r.size());
          renderer_->updateMeshVertices(held->second, static_cast<std::uint32_t>(r.begin), p);
          ++counters_.meshRangeUpdates;
        }
      } else {
        renderer_->setMeshData(held->second, translateMesh(*g));
        ++counters_.meshBuilds;
      }
    } catch (const cov::Error&) {
      flipped.insert(id);  // e.g. non-finite positions: placement skips it with a warning
    }
  }
  if (flipped.empty()) return false;
  // Simplest correct path: drop the instances and meshes of flipped
  // geometries and let placement rebuild what is renderable now.
  removeInstancesOf(flipped);
  for (sg::ContainerId id : flipped) {
    if (auto m = meshes_.find(id); m != meshes_.end()) {
      renderer_->removeMesh(m->second);
      meshes_.erase(m);
    }
    unrenderable_.erase(id);
  }
  return true;
}

void CoverageSceneAdapter::removeInstancesOf(const std::unordered_set<sg::ContainerId>& geometries) {
  for (auto it = instances_.begin(); it != instances_.end();) {
    if (geometries.count(it->second.geometry)) {
      renderer_->removeInstance(it->second.id);
      it = instances_.erase(it);
    } else {
      ++it;
    }
  }
}

void CoverageSceneAdapter::syncTransparency(const sg::Scene& scene, const sg::MergedChanges& changes) {
  // Geometries whose transparency may have changed: a new material on the
  // geometry, or an edit of the material it uses.
  std::unordered_set<sg::ContainerId> materials, geometries;
  for (const auto& [id, e] : changes.entries()) {
    if (e.destroyed) continue;
    if (isMaterial(e.type) && !e.created) materials.insert(id);
    if (e.type == sg::ContainerType::Geometry && e.changed(sg::Geometry::Material)) geometries.insert(id);
  }
  if (materials.empty() && geometries.empty()) return;
  std::unordered_map<sg::ContainerId, bool> transparent;  // per geometry, computed once
  for (auto& [key, placed] : instances_) {
    const auto* g = scene.find<sg::Geometry>(placed.geometry);
    if (!g || !(geometries.count(placed.geometry) || materials.count(g->material()))) continue;
    auto [it, fresh] = transparent.try_emplace(placed.geometry, false);
    if (fresh) it->second = transparentGeometry(scene, placed.geometry);
    if (placed.transparent == it->second) continue;
    renderer_->setInstanceTransparent(placed.id, it->second);
    placed.transparent = it->second;
    ++counters_.transparencyUpdates;
  }
}

void CoverageSceneAdapter::syncTransforms(const sg::Scene& scene, const sg::MergedChanges& changes) {
  std::unordered_set<std::uint32_t> touched;
  for (const auto& [id, e] : changes.entries())
    if (e.type == sg::ContainerType::Transform && e.changed(sg::Transform::Matrix))
      if (auto it = flat_.instancesUnder.find(id); it != flat_.instancesUnder.end())
        touched.insert(it->second.begin(), it->second.end());
  for (std::uint32_t i : touched) {
    FlatNode& node = flat_.instances[i];
    node.world = worldMatrix(scene, node.path);
    auto placed = instances_.find(node.key());
    if (placed == instances_.end() || placed->second.world == node.world) continue;
    renderer_->setInstanceTransform(placed->second.id, node.world);
    placed->second.world = node.world;
    ++counters_.instanceTransforms;
  }
}

void CoverageSceneAdapter::place(const sg::Scene& scene) {
  flat_ = flatten(scene, root_);
  ++counters_.flattenings;
  std::unordered_set<std::string> live;
  for (const FlatNode& node : flat_.instances) {
    const sg::ContainerId object = objectOf(scene, node);
    if (object > std::numeric_limits<cov::ObjectId>::max()) {
      spdlog::warn("coverage: object id {} does not fit 32 bits; skipped", object);
      continue;
    }
    auto mesh = meshFor(scene, node.id);
    if (!mesh) continue;
    std::string key = node.key();
    auto held = instances_.find(key);
    live.insert(key);
    if (held == instances_.end()) {
      const bool transparent = transparentGeometry(scene, node.id);
      cov::Instance inst{*mesh, node.world, static_cast<cov::ObjectId>(object), transparent};
      instances_.emplace(std::move(key), PlacedInstance{renderer_->addInstance(inst), node.id, node.world, transparent});
      continue;
    }
    // The key names the path, so object and geometry are the same; only
    // the matrix can differ.
    PlacedInstance& p = held->second;
    if (p.world != node.world) {
      renderer_->setInstanceTransform(p.id, node.world);
      p.world = node.world;
      ++counters_.instanceTransforms;
    }
  }
  for (auto it = instances_.begin(); it != instances_.end();) {
    if (live.count(it->first)) {
      ++it;
      continue;
    }
    renderer_->removeInstance(it->second.id);
    it = instances_.erase(it);
  }
}

void CoverageSceneAdapter::dropUnusedMeshes(const sg::Scene& scene) {
  std::unordered_set<sg::ContainerId> used;
  for (const auto& [key, p] : instances_) used.insert(p.geometry);
  for (auto it = meshes_.begin(); it != meshes_.end();) {
    if (used.count(it->first) && scene.find(it->first)) {
      ++it;
      continue;
    }
    renderer_->removeMesh(it->second);
    it = meshes_.erase(it);
  }
  for (auto it = unrenderable_.begin(); it != unrenderable_.end();)
    it = scene.find(*it) ? std::next(it) : unrenderable_.erase(it);
}

std::optional<cov::MeshId> CoverageSceneAdapter::meshFor(const sg::Scene& scene, sg::ContainerId id) {
  if (auto it = meshes_.find(id); it != meshes_.end()) return it->second;
  if (unrenderable_.count(id)) return std::nullopt;
  const auto* g = scene.find<sg::Geometry>(id);
  if (auto why = g->invalidReason()) {
    spdlog::warn("coverage: geometry {} '{}' skipped: {}", id, g->name(), *why);
    unrenderable_.insert(id);
    return std::nullopt;
  }
  if (g->triangleCount() == 0) {
    unrenderable_.insert(id);
    return std::nullopt;
  }
  try {
    cov::MeshId mesh = renderer_->addMesh(translateMesh(*g));
    ++counters_.meshBuilds;
    meshes_.emplace(id, mesh);
    return mesh;
  } catch (const cov::Error& e) {
    spdlog::warn("coverage: geometry {} '{}' skipped: {}", id, g->name(), e.what());
    unrenderable_.insert(id);
    return std::nullopt;
  }
}

bool CoverageSceneAdapter::transparentGeometry(const sg::Scene& scene, sg::ContainerId geometry) const {
  const auto* g = scene.find<sg::Geometry>(geometry);
  return g && isTransparent(scene.find(g->material()));
}

}  // namespace tsr::med::coverage_mediator
