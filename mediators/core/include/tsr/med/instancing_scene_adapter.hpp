#pragma once
// The scene adapter of back-ends that share one shape of scene API: meshes,
// per-instance transforms and materials, textures, lights and an
// environment (the Embree path tracer, the Vulkan rasterizer and, through
// an adapter of its id renderer, the coverage pass). Sync runs in numbered
// phases — textures, materials, meshes, placement, environment, leftovers —
// each guarded by a named dirty predicate (dirty_predicates.hpp), so a
// moved transform updates only the instances below it, a material edit
// only that material, and a ranged vertex edit only that range: none of
// them costs a pass over every instance. The back-ends share their handles
// and lights (backends/common), so lights are translated here, once
// (light_translation.hpp). A back-end plugs in through a Types struct:
//
//   struct Types {
//     using Device, Scene, Environment;
//     using Error;                                   // what the back-end throws for data it refuses
//     static constexpr const char* kName;            // logs; attachment "<kName>.hidden" hides geometry
//     static constexpr bool kResizableMeshes;        // setMeshData may change a mesh's size
//     static constexpr sg::FieldMask kMeshFields;    // the geometry fields its meshes hold
//     static constexpr bool kLinesAndPoints;         // it draws them too (else they are skipped, said once)
//     static auto mesh(const sg::Geometry&);         // the back-end's MeshData
//     // A geometry's surface material and the volume inside it (either may be null):
//     static auto material(const sg::Container* surface, const sg::VolumeMaterial* volume,
//                          const std::function<std::optional<TextureId>(sg::ContainerId)>&);
//     static auto texture(const sg::Image&);
//     static Environment background(const sg::Scene&, sg::ContainerId background);
//   };
#include <bit>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include <spdlog/spdlog.h>

#include "tsr/med/instance_placement.hpp"
#include "tsr/med/light_translation.hpp"
#include "tsr/med/scene_adapter.hpp"

namespace tsr::med {

template <class Types>
class InstancingSceneAdapter final : public SceneAdapter {
 public:
  using BackendScene = typename Types::Scene;

  // What the adapter has done, for tests and benchmarks of incremental sync.
  struct Counters {
    std::uint64_t meshBuilds = 0;        // whole meshes handed to the back-end
    std::uint64_t meshRangeUpdates = 0;  // vertex ranges updated in place
    std::uint64_t instanceTransforms = 0;
    std::uint64_t materialUpdates = 0;
    std::uint64_t flattenings = 0;
  };

  InstancingSceneAdapter(std::shared_ptr<typename Types::Device> device, sg::ContainerId root,
                         sg::ContainerId background)
      : device_(std::move(device)), root_(root), background_(background) {}

  BackendScene& scene() { return *scene_; }
  const BackendScene& scene() const { return *scene_; }
  bool converted() const { return scene_ != nullptr; }
  const typename Types::Environment& environment() const { return environment_; }
  Counters counters() const {
    Counters c = counters_;
    c.instanceTransforms = placement_.transformUpdates;
    c.flattenings = placement_.flattenings;
    return c;
  }

 protected:
  void convert(const sg::Scene& scene) override {
    // Handles die with the old scene; clear the maps before anything is added.
    scene_.reset();
    meshes_.clear();
    unrenderable_.clear();
    materials_.clear();
    textures_.clear();
    placement_.clear();
    scene_ = std::make_unique<BackendScene>(device_);
    placement_.place(scene, root_, *scene_, hooks(scene));
    setEnvironment(scene);
  }

  void sync(const sg::Scene& scene, const sg::MergedChanges& changes) override {
    // Phase 0: does the shape of the graph change? Then placement is redone
    // (a diff: surviving instances keep their back-end objects).
    bool structural = false;
    bool orphans = false;  // something may no longer be used: look for leftovers
    for (const auto& [id, e] : changes.entries()) {
      structural |= structureDirty(e);
      orphans |= mayOrphan(e, scene.find(id));
    }
    syncTextures(scene, changes);                       // phase 1
    syncMaterials(scene, changes);                      // phase 2
    if (syncMeshes(scene, changes)) structural = true;  // phase 3
    if (structural)                                     // phase 4
      placement_.place(scene, root_, *scene_, hooks(scene));
    else
      placement_.moveEdited(scene, changes, *scene_, hooks(scene));
    if (backgroundDirty(scene, changes)) setEnvironment(scene);  // phase 5
    if (structural || orphans) dropUnused(scene);                // phase 6
  }

 private:
  static bool references(const sg::Container& c, sg::ContainerId target) {
    bool uses = false;
    forEachReference(c, [&](sg::ContainerId r) { uses |= r == target; });
    return uses;
  }
  template <class Fn>
  static void forEachReference(const sg::Container& c, Fn&& fn) {
    for (sg::FieldMask refs = c.referenceFields(); refs; refs &= refs - 1)
      c.forEachReference(static_cast<sg::FieldIndex>(std::countr_zero(refs)), fn);
  }
  bool hidden(const sg::Container& c) const {
    const auto* v = c.attachment(std::string(Types::kName) + ".hidden");
    const auto* i = v ? std::get_if<std::int64_t>(v) : nullptr;
    return i && *i != 0;
  }
  auto textures(const sg::Scene& scene) {
    return [this, &scene](sg::ContainerId image) { return textureFor(scene, image); };
  }

  void syncTextures(const sg::Scene& scene, const sg::MergedChanges& changes) {
    for (const auto& [id, e] : changes.entries()) {
      if (!imageDirty(e)) continue;
      auto held = textures_.find(id);
      if (held == textures_.end()) continue;
      // New texture first, then the materials that use it, then the old one.
      auto old = held->second;
      textures_.erase(held);
      textureFor(scene, id);
      for (auto& [key, handle] : materials_)
        if (usesImage(scene, key, id)) scene_->setMaterial(handle, translate(scene, key));
      scene_->removeTexture(old);
    }
  }

  // A surface or volume edit updates the back-end materials made of it.
  void syncMaterials(const sg::Scene& scene, const sg::MergedChanges& changes) {
    for (const auto& [id, e] : changes.entries()) {
      if (!materialDirty(e)) continue;
      for (auto& [key, handle] : materials_) {
        if (key.first != id && key.second != id) continue;
        scene_->setMaterial(handle, translate(scene, key));
        ++counters_.materialUpdates;
      }
    }
  }

  // Returns true when placement must be redone (meshes were dropped).
  bool syncMeshes(const sg::Scene& scene, const sg::MergedChanges& changes) {
    using G = sg::Geometry;
    std::unordered_set<sg::ContainerId> rebuild;
    for (const auto& [id, e] : changes.entries()) {
      if (materialBindingDirty(e)) placement_.rebind(id, materialOfGeometry(scene, id), *scene_);
      if (!meshDirty(e, Types::kMeshFields)) continue;
      auto held = meshes_.find(id);
      if (held == meshes_.end() && !unrenderable_.count(id)) continue;  // not (yet) instanced here
      const auto* g = scene.find<G>(id);
      if (held == meshes_.end() && g && !renderable(*g)) continue;  // skipped, and still skipped: said once
      if (held == meshes_.end() || !renderable(*g)) {               // flips between skipped and rendered
        rebuild.insert(id);
        continue;
      }
      try {
        if (pointsRangeOnly(e, Types::kMeshFields)) {
          updateRanges(*g, held->second, e);
        } else if constexpr (Types::kResizableMeshes) {
          scene_->setMeshData(held->second, Types::mesh(*g));  // new topology, in place
          ++counters_.meshBuilds;
        } else {
          rebuild.insert(id);  // new topology: the mesh and its instances are built again
        }
      } catch (const typename Types::Error& error) {
        spdlog::warn("{}: geometry {} '{}' refused: {}", Types::kName, id, g->name(), error.what());
        rebuild.insert(id);  // placement tries again and skips it with a warning
      }
    }
    for (sg::ContainerId id : rebuild) {
      placement_.removeInstancesOf(id, *scene_);
      if (auto m = meshes_.find(id); m != meshes_.end()) {
        scene_->removeMesh(m->second);
        meshes_.erase(m);
      }
      unrenderable_.erase(id);
    }
    return !rebuild.empty();
  }

  // Vertex edits by range keep the topology: update those ranges only.
  void updateRanges(const sg::Geometry& g, backend::MeshId mesh, const ChangeEntry& e) {
    using G = sg::Geometry;
    const auto* pos = e.rangedEdit(G::Positions);
    const auto* nrm = (Types::kMeshFields & sg::fieldBit(G::Normals)) ? e.rangedEdit(G::Normals) : nullptr;
    sg::RangeSet runs;
    for (const auto* edit : {pos, nrm})
      if (edit)
        for (const auto& r : edit->ranges) runs.add(r);
    for (const auto& r : runs.ranges()) {
      backend::VertexEdit edit{.positions = g.positions(),
                               .first = static_cast<std::uint32_t>(r.begin),
                               .count = static_cast<std::uint32_t>(r.size())};
      // Normals travel only when they were edited; the back-end keeps the rest.
      if (nrm && !g.normals().empty()) edit.normals = g.normals();
      scene_->updateMeshVertices(mesh, edit);
      ++counters_.meshRangeUpdates;
    }
  }

  static bool drawn(sg::GeometryPrimitive p) { return Types::kLinesAndPoints || p == sg::GeometryPrimitive::Triangles; }
  static bool renderable(const sg::Geometry& g) {
    return !g.invalidReason() && g.primitiveCount() > 0 && drawn(g.primitive());
  }

  bool backgroundDirty(const sg::Scene& scene, const sg::MergedChanges& changes) const {
    if (background_ == sg::kNoContainer) return false;
    bool dirty = changes.entries().count(background_) != 0;
    if (const auto* b = scene.find<sg::Background>(background_))
      dirty |= changes.entries().count(b->environment()) != 0 || changes.entries().count(b->medium()) != 0;
    return dirty;
  }

  typename InstancePlacement<Types>::Hooks hooks(const sg::Scene& scene) {
    typename InstancePlacement<Types>::Hooks h;
    h.mesh = [this, &scene](sg::ContainerId geometry) -> std::optional<backend::MeshId> {
      const auto* g = scene.find<sg::Geometry>(geometry);
      if (!g || hidden(*g)) return std::nullopt;
      return meshFor(scene, geometry);
    };
    h.material = [this, &scene](sg::ContainerId geometry) { return materialOfGeometry(scene, geometry); };
    h.light = [&scene](const FlatNode& node) -> std::optional<backend::Light> {
      const auto* light = scene.find<sg::Light>(node.id);
      if (!light) return std::nullopt;
      return translateLight(*light, node.world);
    };
    return h;
  }

  void setEnvironment(const sg::Scene& scene) {
    environment_ = Types::background(scene, background_);
    scene_->setEnvironment(environment_);
  }

  // Removes back-end meshes, materials and textures nothing uses any more;
  // the placement's indexes answer "used?", so this costs the number of
  // meshes and materials, not of instances.
  void dropUnused(const sg::Scene& scene) {
    std::erase_if(meshes_, [&](const auto& kv) {
      if (placement_.uses(kv.first) && scene.find(kv.first)) return false;
      placement_.removeInstancesOf(kv.first, *scene_);  // a destroyed geometry's, until placement ran
      scene_->removeMesh(kv.second);
      return true;
    });
    std::erase_if(unrenderable_, [&](sg::ContainerId id) { return !scene.find(id); });
    std::erase_if(materials_, [&](const auto& kv) {
      if (placement_.usesMaterial(kv.second)) return false;
      scene_->removeMaterial(kv.second);
      return true;
    });
    std::unordered_set<sg::ContainerId> usedImages;
    for (const auto& [key, handle] : materials_)
      for (sg::ContainerId part : {key.first, key.second})
        if (const sg::Container* m = scene.find(part))
          forEachReference(*m, [&](sg::ContainerId r) { usedImages.insert(r); });
    std::erase_if(textures_, [&](const auto& kv) {
      if (usedImages.count(kv.first)) return false;
      scene_->removeTexture(kv.second);
      return true;
    });
  }

  std::optional<backend::MeshId> meshFor(const sg::Scene& scene, sg::ContainerId id) {
    if (auto it = meshes_.find(id); it != meshes_.end()) return it->second;
    if (unrenderable_.count(id)) return std::nullopt;
    const auto* g = scene.find<sg::Geometry>(id);
    if (auto why = g->invalidReason()) {
      spdlog::warn("{}: geometry {} '{}' skipped: {}", Types::kName, id, g->name(), *why);
      unrenderable_.insert(id);
      return std::nullopt;
    }
    if (!drawn(g->primitive())) {
      // Said at the default level: a drawing's lines must not vanish in
      // silence. Once: a CAD file may hold thousands of them.
      const char* what = g->primitive() == sg::GeometryPrimitive::Lines ? "lines" : "points";
      if (!linesSaid_)
        spdlog::warn("{}: geometry {} '{}' skipped: {} draws no lines or points (the others skipped as well are "
                     "named at debug level)",
                     Types::kName, id, g->name(), Types::kName);
      else
        spdlog::debug("{}: geometry {} '{}' of {} skipped", Types::kName, id, g->name(), what);
      linesSaid_ = true;
      unrenderable_.insert(id);
      return std::nullopt;
    }
    if (g->primitiveCount() == 0) {
      unrenderable_.insert(id);
      return std::nullopt;
    }
    try {
      auto mesh = scene_->addMesh(Types::mesh(*g));
      ++counters_.meshBuilds;
      meshes_.emplace(id, mesh);
      return mesh;
    } catch (const typename Types::Error& error) {
      spdlog::warn("{}: geometry {} '{}' skipped: {}", Types::kName, id, g->name(), error.what());
      unrenderable_.insert(id);
      return std::nullopt;
    }
  }

  // A back-end material is a geometry's surface material and its volume.
  using MaterialKey = std::pair<sg::ContainerId, sg::ContainerId>;

  auto translate(const sg::Scene& scene, const MaterialKey& key) {
    return Types::material(scene.find(key.first), scene.find<sg::VolumeMaterial>(key.second), textures(scene));
  }

  bool usesImage(const sg::Scene& scene, const MaterialKey& key, sg::ContainerId image) const {
    const sg::Container* surface = scene.find(key.first);
    const sg::Container* volume = scene.find(key.second);
    return (surface && references(*surface, image)) || (volume && references(*volume, image));
  }

  backend::MaterialId materialFor(const sg::Scene& scene, const MaterialKey& key) {
    if (auto it = materials_.find(key); it != materials_.end()) return it->second;
    auto m = scene_->addMaterial(translate(scene, key));
    materials_.emplace(key, m);
    return m;
  }

  backend::MaterialId materialOfGeometry(const sg::Scene& scene, sg::ContainerId geometry) {
    const auto* g = scene.find<sg::Geometry>(geometry);
    return materialFor(scene, g ? MaterialKey{g->material(), g->volume()} : MaterialKey{});
  }

  std::optional<backend::TextureId> textureFor(const sg::Scene& scene, sg::ContainerId id) {
    if (auto it = textures_.find(id); it != textures_.end()) return it->second;
    const auto* image = scene.find<sg::Image>(id);
    if (!image) return std::nullopt;
    if (auto why = image->invalidReason()) {
      spdlog::warn("{}: image {} '{}' skipped: {}", Types::kName, id, image->name(), *why);
      return std::nullopt;
    }
    if (image->width() == 0 || image->height() == 0) return std::nullopt;
    auto t = scene_->addTexture(Types::texture(*image));
    textures_.emplace(id, t);
    return t;
  }

  std::shared_ptr<typename Types::Device> device_;
  sg::ContainerId root_, background_;
  std::unique_ptr<BackendScene> scene_;
  typename Types::Environment environment_;
  InstancePlacement<Types> placement_;
  std::unordered_map<sg::ContainerId, backend::MeshId> meshes_;
  std::unordered_set<sg::ContainerId> unrenderable_;      // invalid or empty geometry, skipped
  bool linesSaid_ = false;                                // lines or points were skipped with a warning
  std::map<MaterialKey, backend::MaterialId> materials_;  // kNoContainer: the default, or no volume
  std::unordered_map<sg::ContainerId, backend::TextureId> textures_;
  Counters counters_;
};

}  // namespace tsr::med
