#pragma once
// The geometry instances and lights a back-end holds for the flattened scene,
// keyed by FlatKey, and the updates every instancing adapter needs: a diff
// against a fresh flattening when the graph's shape changed, moving only
// what sits below edited transforms, and per-geometry / per-material
// indexes so an edit of one geometry or one material costs what uses it,
// not every instance. Back-ends whose scene API has
// addInstance / setInstanceTransform / setInstanceMaterial / removeInstance
// and addLight / setLight / removeLight, in the shared vocabulary's handles
// and lights (backends/common), plug in through a types struct:
//   struct Types { using Scene; };
// A Types with `static std::optional<ObjectId> object(const sg::Scene&, const FlatNode&)`
// also tags each instance with an object id (addInstance's fourth argument);
// none skips the instance.
#include <functional>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "tsr/backend/ids.hpp"
#include "tsr/backend/light.hpp"
#include "tsr/med/dirty_predicates.hpp"
#include "tsr/med/scene_flattening.hpp"

namespace tsr::med {

template <class Types>
concept TagsObjects = requires(const sg::Scene& scene, const FlatNode& node) {
  Types::object(scene, node);
};

// A back-end scene that blurs motion takes an instance's transform at the
// frame's time and at the end of its interval (equal: it keeps still).
template <class Scene, class InstanceId>
concept BlursMotion = requires(Scene& scene, InstanceId id, const glm::mat4& m) {
  scene.setInstanceTransform(id, m, m);
};

template <class Types>
class InstancePlacement {
 public:
  using BackendScene = typename Types::Scene;
  using MaterialId = backend::MaterialId;

  struct Placed {
    backend::InstanceId id;
    sg::ContainerId geometry;
    glm::mat4 world;
    MaterialId material;
    glm::mat4 worldAtEnd;  // the world matrix at the frame interval's end (world when still)
  };
  static constexpr bool kBlursMotion = BlursMotion<BackendScene, backend::InstanceId>;

  // What the adapter decides; the placement only applies it.
  struct Hooks {
    // The back-end mesh of a geometry, or none when it is not rendered here.
    std::function<std::optional<backend::MeshId>(sg::ContainerId geometry)> mesh;
    std::function<MaterialId(sg::ContainerId geometry)> material;
    // A light placed by its world matrix, or none.
    std::function<std::optional<backend::Light>(const FlatNode& node)> light;
  };

  void clear() {
    flat_ = {};
    instances_.clear();
    byGeometry_.clear();
    materialUsers_.clear();
    lights_.clear();
  }

  // Re-flattens from `root` and applies the difference: surviving instances
  // keep their back-end objects and only get what changed.
  void place(const sg::Scene& scene, sg::ContainerId root, BackendScene& backend, const Hooks& hooks) {
    flat_ = flatten(scene, root);
    ++flattenings;
    std::unordered_set<FlatKey> live;
    for (const FlatNode& node : flat_.instances) {
      auto held = instances_.find(node.key);
      if (held != instances_.end() && held->second.geometry != node.id) {  // the key moved to another geometry
        remove(held, backend);
        held = instances_.end();
      }
      auto mesh = hooks.mesh(node.id);
      if (!mesh) continue;
      MaterialId material = hooks.material(node.id);
      if (held == instances_.end()) {
        if (add(scene, node, *mesh, material, backend)) live.insert(node.key);
        continue;
      }
      live.insert(node.key);
      const glm::mat4 end = worldAtEnd(scene, node);
      if (held->second.world != node.world || held->second.worldAtEnd != end)
        move(held->second, node.world, end, backend);
      setMaterial(held->second, material, backend);
    }
    for (auto it = instances_.begin(); it != instances_.end();)
      it = live.count(it->first) ? std::next(it) : remove(it, backend);
    std::unordered_set<FlatKey> liveLights;
    for (const FlatNode& node : flat_.lights)
      if (placeLight(node, backend, hooks)) liveLights.insert(node.key);
    std::erase_if(lights_, [&](const auto& kv) {
      if (liveLights.count(kv.first)) return false;
      backend.removeLight(kv.second);
      return true;
    });
  }

  // Moves the instances and lights below transforms whose matrix changed,
  // and re-places lights whose own fields changed.
  void moveEdited(const sg::Scene& scene, const sg::MergedChanges& changes, BackendScene& backend, const Hooks& hooks) {
    std::unordered_set<std::uint32_t> instances, lights;
    for (const auto& [id, e] : changes.entries()) {
      if (transformDirty(e)) {
        if (auto it = flat_.instancesUnder.find(id); it != flat_.instancesUnder.end())
          instances.insert(it->second.begin(), it->second.end());
        if (auto it = flat_.lightsUnder.find(id); it != flat_.lightsUnder.end())
          lights.insert(it->second.begin(), it->second.end());
      }
      if (lightDirty(e))
        for (std::uint32_t i = 0; i < flat_.lights.size(); ++i)
          if (flat_.lights[i].id == id) lights.insert(i);
    }
    for (std::uint32_t i : instances) {
      FlatNode& node = flat_.instances[i];
      node.world = worldMatrix(scene, node.path);
      node.moves = pathMoves(scene, node.path);
      auto placed = instances_.find(node.key);
      if (placed == instances_.end()) continue;  // not rendered here
      const glm::mat4 end = worldAtEnd(scene, node);
      if (placed->second.world == node.world && placed->second.worldAtEnd == end) continue;
      move(placed->second, node.world, end, backend);
    }
    for (std::uint32_t i : lights) {
      FlatNode& node = flat_.lights[i];
      node.world = worldMatrix(scene, node.path);
      placeLight(node, backend, hooks);
    }
  }

  // Gives every instance of `geometry` the material `material`.
  void rebind(sg::ContainerId geometry, MaterialId material, BackendScene& backend) {
    if (auto keys = byGeometry_.find(geometry); keys != byGeometry_.end())
      for (FlatKey key : keys->second) setMaterial(instances_.at(key), material, backend);
  }

  // Removes every instance of `geometry` (its mesh is about to go).
  void removeInstancesOf(sg::ContainerId geometry, BackendScene& backend) {
    auto keys = byGeometry_.find(geometry);
    if (keys == byGeometry_.end()) return;
    for (FlatKey key : std::unordered_set<FlatKey>(keys->second)) remove(instances_.find(key), backend);
  }

  bool uses(sg::ContainerId geometry) const { return byGeometry_.count(geometry) != 0; }
  bool usesMaterial(const MaterialId& material) const { return materialUsers_.count(material) != 0; }
  const std::unordered_map<FlatKey, Placed>& instances() const { return instances_; }
  const FlatScene& flat() const { return flat_; }

  std::uint64_t flattenings = 0;
  std::uint64_t transformUpdates = 0;

 private:
  using Iterator = typename std::unordered_map<FlatKey, Placed>::iterator;

  bool add(const sg::Scene& scene, const FlatNode& node, backend::MeshId mesh, MaterialId material,
           BackendScene& backend) {
    backend::InstanceId id;
    if constexpr (TagsObjects<Types>) {
      auto object = Types::object(scene, node);
      if (!object) return false;
      id = backend.addInstance(mesh, material, node.world, *object);
    } else {
      id = backend.addInstance(mesh, material, node.world);
    }
    const glm::mat4 end = worldAtEnd(scene, node);
    if constexpr (kBlursMotion)
      if (end != node.world) backend.setInstanceTransform(id, node.world, end);
    instances_.emplace(node.key, Placed{id, node.id, node.world, material, end});
    byGeometry_[node.id].insert(node.key);
    ++materialUsers_[material];
    return true;
  }

  Iterator remove(Iterator it, BackendScene& backend) {
    const Placed& p = it->second;
    backend.removeInstance(p.id);
    if (auto keys = byGeometry_.find(p.geometry);
        keys != byGeometry_.end() && keys->second.erase(it->first) && keys->second.empty())
      byGeometry_.erase(keys);
    release(p.material);
    return instances_.erase(it);
  }

  // Where the instance is at the end of the frame interval: only for
  // back-ends that blur motion (the others draw it at the frame's time).
  static glm::mat4 worldAtEnd(const sg::Scene& scene, const FlatNode& node) {
    if constexpr (kBlursMotion)
      if (node.moves) return worldMatrix(scene, node.path, sg::FrameTime::End);
    (void)scene;
    return node.world;
  }

  void move(Placed& p, const glm::mat4& world, const glm::mat4& end, BackendScene& backend) {
    if constexpr (kBlursMotion)
      backend.setInstanceTransform(p.id, world, end);
    else
      backend.setInstanceTransform(p.id, world);
    p.world = world;
    p.worldAtEnd = end;
    ++transformUpdates;
  }

  void setMaterial(Placed& p, MaterialId material, BackendScene& backend) {
    if (p.material == material) return;
    backend.setInstanceMaterial(p.id, material);
    release(p.material);
    ++materialUsers_[material];
    p.material = material;
  }

  void release(const MaterialId& material) {
    if (auto n = materialUsers_.find(material); n != materialUsers_.end() && --n->second == 0) materialUsers_.erase(n);
  }

  bool placeLight(const FlatNode& node, BackendScene& backend, const Hooks& hooks) {
    auto light = hooks.light(node);
    if (!light) return false;
    auto held = lights_.find(node.key);
    if (held == lights_.end())
      lights_.emplace(node.key, backend.addLight(*light));
    else
      backend.setLight(held->second, *light);
    return true;
  }

  FlatScene flat_;
  std::unordered_map<FlatKey, Placed> instances_;
  std::unordered_map<sg::ContainerId, std::unordered_set<FlatKey>> byGeometry_;
  std::unordered_map<MaterialId, std::size_t> materialUsers_;
  std::unordered_map<FlatKey, backend::LightId> lights_;
};

}  // namespace tsr::med
