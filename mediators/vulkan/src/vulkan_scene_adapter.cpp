#include "vulkan_scene_adapter.hpp"

#include <bit>

#include <spdlog/spdlog.h>

#include "translation.hpp"

namespace tsr::med::vulkan_mediator {

namespace {
// Geometry flagged with this attachment (non-zero) is not rendered here.
constexpr const char* kHiddenAttachment = "vulkan.hidden";

bool hidden(const sg::Container& c) {
  const auto* v = c.attachment(kHiddenAttachment);
  const auto* i = v ? std::get_if<std::int64_t>(v) : nullptr;
  return i && *i != 0;
}

bool isNode(sg::ContainerType t) { return (sg::typeBit(t) & sg::kNodeTypes) != 0; }

bool references(const sg::Container& c, sg::ContainerId target) {
  bool uses = false;
  for (sg::FieldMask refs = c.referenceFields(); refs; refs &= refs - 1)
    c.forEachReference(static_cast<sg::FieldIndex>(std::countr_zero(refs)), [&](sg::ContainerId r) { uses |= r == target; });
  return uses;
}
}  // namespace

VulkanSceneAdapter::VulkanSceneAdapter(std::shared_ptr<vk::Device> device, sg::ContainerId root,
                                       sg::ContainerId background)
    : device_(std::move(device)), root_(root), background_(background) {}

void VulkanSceneAdapter::convert(const sg::Scene& scene) {
  // Handles die with the old scene; clear the maps before anything is added.
  scene_.reset();
  meshes_.clear();
  unrenderable_.clear();
  materials_.clear();
  textures_.clear();
  placement_.clear();
  scene_ = std::make_unique<vk::Scene>(device_);
  placement_.place(scene, root_, *scene_, hooks(scene));
  setEnvironment(scene);
}

void VulkanSceneAdapter::sync(const sg::Scene& scene, const sg::MergedChanges& changes) {
  // Phase 0: does the shape of the graph change? Then placement is redone
  // (a diff: surviving instances keep their back-end objects).
  bool structural = false;
  bool mayOrphan = false;  // something may no longer be used: look for leftovers
  for (const auto& [id, e] : changes.entries()) {
    if (e.destroyed || (e.type == sg::ContainerType::Geometry && e.changed(sg::Geometry::Material)) ||
        (e.type != sg::ContainerType::Transform && e.type != sg::ContainerType::Light && e.mask != 0))
      mayOrphan = true;
    if (!isNode(e.type)) continue;
    if (e.created || e.destroyed || e.changed(sg::Container::kAttachments)) structural = true;
    if (sg::isParentType(e.type) && e.changed(sg::Group::Children)) structural = true;
  }
  syncTextures(scene, changes);  // phase 1
  syncMaterials(scene, changes);  // phase 2
  if (syncMeshes(scene, changes)) structural = true;  // phase 3
  if (structural)  // phase 4
    placement_.place(scene, root_, *scene_, hooks(scene));
  else
    placement_.moveEdited(scene, changes, *scene_, hooks(scene));
  bool backgroundChanged = background_ != sg::kNoContainer && changes.entries().count(background_);
  if (const auto* b = scene.find<sg::Background>(background_))
    backgroundChanged |= changes.entries().count(b->environment()) != 0;
  if (backgroundChanged) setEnvironment(scene);  // phase 5
  if (structural || mayOrphan) dropUnused(scene);
}

void VulkanSceneAdapter::syncTextures(const sg::Scene& scene, const sg::MergedChanges& changes) {
  for (const auto& [id, e] : changes.entries()) {
    if (e.type != sg::ContainerType::Image || e.created || e.destroyed) continue;
    auto held = textures_.find(id);
    if (held == textures_.end()) continue;
    // New texture first, then the materials that use it, then the old one.
    vk::TextureId old = held->second;
    textures_.erase(held);
    textureFor(scene, id);
    for (auto& [matId, handle] : materials_)
      if (const sg::Container* m = scene.find(matId); m && references(*m, id))
        scene_->setMaterial(handle, translateMaterial(m, [&](sg::ContainerId i) { return textureFor(scene, i); }));
    scene_->removeTexture(old);
  }
}

void VulkanSceneAdapter::syncMaterials(const sg::Scene& scene, const sg::MergedChanges& changes) {
  for (const auto& [id, e] : changes.entries()) {
    if (e.destroyed || e.created) continue;
    auto held = materials_.find(id);
    if (held == materials_.end()) continue;
    scene_->setMaterial(held->second,
                        translateMaterial(scene.find(id), [&](sg::ContainerId i) { return textureFor(scene, i); }));
    ++counters_.materialUpdates;
  }
}

bool VulkanSceneAdapter::syncMeshes(const sg::Scene& scene, const sg::MergedChanges& changes) {
  using G = sg::Geometry;
  const sg::FieldMask shape = sg::fieldBit(G::Positions) | sg::fieldBit(G::Normals) | sg::fieldBit(G::Uvs) |
                              sg::fieldBit(G::Indices) | sg::fieldBit(G::Motion) | sg::fieldBit(G::Colors);
  const sg::FieldMask ranged = sg::fieldBit(G::Positions) | sg::fieldBit(G::Normals);
  std::unordered_set<sg::ContainerId> rebuild;
  for (const auto& [id, e] : changes.entries()) {
    if (e.type != sg::ContainerType::Geometry || e.created || e.destroyed) continue;
    const auto* g = scene.find<G>(id);
    if (e.changed(G::Material)) {
      vk::MaterialId m = materialOfGeometry(scene, id);
      for (auto& [key, placed] : placement_.instances())
        if (placed.geometry == id && placed.material != m) {
          scene_->setInstanceMaterial(placed.id, m);
          placed.material = m;
        }
    }
    if (!(e.mask & shape)) continue;
    auto held = meshes_.find(id);
    if (held == meshes_.end() && !unrenderable_.count(id)) continue;  // not (yet) instanced here
    bool renderable = !g->invalidReason() && g->triangleCount() > 0;
    // Vertex edits by range keep the topology: upload those ranges only.
    const auto* pos = e.rangedEdit(G::Positions);
    const auto* nrm = e.rangedEdit(G::Normals);
    bool onlyRanges = !(e.mask & shape & ~ranged) && (!e.changed(G::Positions) || pos) && (!e.changed(G::Normals) || nrm);
    if (held == meshes_.end() || !renderable || !onlyRanges) {
      // State flips between skipped and rendered, or new topology: the mesh
      // is built again and its instances placed again (vk meshes are immutable
      // in size, instances are bound to one).
      rebuild.insert(id);
      continue;
    }
    sg::RangeSet runs;
    for (const auto* edit : {pos, nrm})
      if (edit)
        for (const auto& r : edit->ranges) runs.add(r);
    for (const auto& r : runs.ranges()) {
      std::span<const glm::vec3> p(g->positions().data() + r.begin, r.size());
      std::span<const glm::vec3> n;
      if (nrm && !g->normals().empty()) n = std::span<const glm::vec3>(g->normals().data() + r.begin, r.size());
      scene_->updateMeshVertices(held->second, static_cast<std::uint32_t>(r.begin), p, n);
      ++counters_.meshRangeUpdates;
    }
  }
  if (rebuild.empty()) return false;
  dropMeshes(rebuild);
  return true;
}

void VulkanSceneAdapter::dropMeshes(const std::unordered_set<sg::ContainerId>& geometries) {
  auto& instances = placement_.instances();
  for (auto it = instances.begin(); it != instances.end();) {
    if (geometries.count(it->second.geometry)) {
      scene_->removeInstance(it->second.id);
      it = instances.erase(it);
    } else {
      ++it;
    }
  }
  for (sg::ContainerId id : geometries) {
    if (auto m = meshes_.find(id); m != meshes_.end()) {
      scene_->removeMesh(m->second);
      meshes_.erase(m);
    }
    unrenderable_.erase(id);
  }
}

InstancePlacement<VulkanSceneAdapter::Types>::Hooks VulkanSceneAdapter::hooks(const sg::Scene& scene) {
  InstancePlacement<Types>::Hooks h;
  h.mesh = [this, &scene](sg::ContainerId geometry) -> std::optional<vk::MeshId> {
    const auto* g = scene.find<sg::Geometry>(geometry);
    if (!g || hidden(*g)) return std::nullopt;
    return meshFor(scene, geometry);
  };
  h.material = [this, &scene](sg::ContainerId geometry) { return materialOfGeometry(scene, geometry); };
  h.light = [&scene](const FlatNode& node) -> std::optional<vk::Light> {
    const auto* light = scene.find<sg::Light>(node.id);
    if (!light) return std::nullopt;
    return translateLight(*light, node.world);
  };
  return h;
}

VulkanSceneAdapter::Counters VulkanSceneAdapter::counters() const {
  Counters c = counters_;
  c.instanceTransforms = placement_.transformUpdates;
  c.flattenings = placement_.flattenings;
  return c;
}

void VulkanSceneAdapter::setEnvironment(const sg::Scene& scene) {
  environment_ = translateBackground(scene, background_);
  scene_->setEnvironment(environment_);
}

void VulkanSceneAdapter::dropUnused(const sg::Scene& scene) {
  std::unordered_set<sg::ContainerId> usedMeshes;
  std::unordered_set<std::uint32_t> usedMaterials;
  for (const auto& [key, p] : placement_.instances()) {
    usedMeshes.insert(p.geometry);
    usedMaterials.insert(vk::index(p.material));
  }
  for (auto it = meshes_.begin(); it != meshes_.end();) {
    if (usedMeshes.count(it->first) && scene.find(it->first)) {
      ++it;
      continue;
    }
    scene_->removeMesh(it->second);
    it = meshes_.erase(it);
  }
  for (auto it = materials_.begin(); it != materials_.end();) {
    if (usedMaterials.count(vk::index(it->second))) {
      ++it;
      continue;
    }
    scene_->removeMaterial(it->second);
    it = materials_.erase(it);
  }
  // Textures no material uses any more.
  std::unordered_set<sg::ContainerId> usedImages;
  for (const auto& [matId, handle] : materials_)
    if (const sg::Container* m = scene.find(matId))
      for (sg::FieldMask refs = m->referenceFields(); refs; refs &= refs - 1)
        m->forEachReference(static_cast<sg::FieldIndex>(std::countr_zero(refs)), [&](sg::ContainerId r) { usedImages.insert(r); });
  for (auto it = textures_.begin(); it != textures_.end();) {
    if (usedImages.count(it->first)) {
      ++it;
      continue;
    }
    scene_->removeTexture(it->second);
    it = textures_.erase(it);
  }
}

std::optional<vk::MeshId> VulkanSceneAdapter::meshFor(const sg::Scene& scene, sg::ContainerId id) {
  if (auto it = meshes_.find(id); it != meshes_.end()) return it->second;
  if (unrenderable_.count(id)) return std::nullopt;
  const auto* g = scene.find<sg::Geometry>(id);
  if (auto why = g->invalidReason()) {
    spdlog::warn("vulkan: geometry {} '{}' skipped: {}", id, g->name(), *why);
    unrenderable_.insert(id);
    return std::nullopt;
  }
  if (g->triangleCount() == 0) {
    unrenderable_.insert(id);
    return std::nullopt;
  }
  vk::MeshId mesh = scene_->addMesh(translateMesh(*g));
  ++counters_.meshBuilds;
  meshes_.emplace(id, mesh);
  return mesh;
}

vk::MaterialId VulkanSceneAdapter::materialFor(const sg::Scene& scene, sg::ContainerId id) {
  if (auto it = materials_.find(id); it != materials_.end()) return it->second;
  vk::MaterialId m = scene_->addMaterial(
      translateMaterial(scene.find(id), [&](sg::ContainerId image) { return textureFor(scene, image); }));
  materials_.emplace(id, m);
  return m;
}

vk::MaterialId VulkanSceneAdapter::materialOfGeometry(const sg::Scene& scene, sg::ContainerId geometry) {
  const auto* g = scene.find<sg::Geometry>(geometry);
  return materialFor(scene, g ? g->material() : sg::kNoContainer);
}

std::optional<vk::TextureId> VulkanSceneAdapter::textureFor(const sg::Scene& scene, sg::ContainerId id) {
  if (auto it = textures_.find(id); it != textures_.end()) return it->second;
  const auto* image = scene.find<sg::Image>(id);
  if (!image) return std::nullopt;
  if (auto why = image->invalidReason()) {
    spdlog::warn("vulkan: image {} '{}' skipped: {}", id, image->name(), *why);
    return std::nullopt;
  }
  if (image->width() == 0 || image->height() == 0) return std::nullopt;
  vk::TextureId t = scene_->addTexture(translateImage(*image));
  textures_.emplace(id, t);
  return t;
}

}  // namespace tsr::med::vulkan_mediator
