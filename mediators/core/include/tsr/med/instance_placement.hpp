#pragma once
// The geometry instances and lights a back-end holds for the flattened scene,
// keyed by path, and the two updates every instancing adapter needs: a diff
// against a fresh flattening when the graph's shape changed, and moving only
// what sits below edited transforms. Back-ends whose scene API has
// addInstance / setInstanceTransform / setInstanceMaterial / removeInstance
// and addLight / setLight / removeLight plug in through a types struct:
//   struct Types { using Scene, MeshId, MaterialId, InstanceId, LightId, Light; };
#include <functional>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "tsr/med/scene_flattening.hpp"
#include "tsr/sg/merged_changes.hpp"

namespace tsr::med {

template <class Types>
class InstancePlacement {
 public:
  using BackendScene = typename Types::Scene;
  using MaterialId = typename Types::MaterialId;

  struct Placed {
    typename Types::InstanceId id;
    sg::ContainerId geometry;
    glm::mat4 world;
    MaterialId material;
  };

  // What the adapter decides; the placement only applies it.
  struct Hooks {
    // The back-end mesh of a geometry, or none when it is not rendered here.
    std::function<std::optional<typename Types::MeshId>(sg::ContainerId geometry)> mesh;
    std::function<MaterialId(sg::ContainerId geometry)> material;
    // A light placed by its world matrix, or none.
    std::function<std::optional<typename Types::Light>(const FlatNode& node)> light;
  };

  void clear() {
    flat_ = {};
    instances_.clear();
    lights_.clear();
  }

  // Re-flattens from `root` and applies the difference: surviving instances
  // keep their back-end objects and only get what changed.
  void place(const sg::Scene& scene, sg::ContainerId root, BackendScene& backend, const Hooks& hooks) {
    flat_ = flatten(scene, root);
    ++flattenings;
    std::unordered_set<std::string> live;
    for (const FlatNode& node : flat_.instances) {
      auto mesh = hooks.mesh(node.id);
      if (!mesh) continue;
      std::string key = node.key();
      live.insert(key);
      MaterialId material = hooks.material(node.id);
      auto held = instances_.find(key);
      if (held == instances_.end()) {
        instances_.emplace(key, Placed{backend.addInstance(*mesh, material, node.world), node.id, node.world, material});
        continue;
      }
      Placed& p = held->second;
      if (p.world != node.world) {
        backend.setInstanceTransform(p.id, node.world);
        p.world = node.world;
        ++transformUpdates;
      }
      if (p.material != material) {
        backend.setInstanceMaterial(p.id, material);
        p.material = material;
      }
    }
    eraseExcept(instances_, live, [&](const Placed& p) { backend.removeInstance(p.id); });
    std::unordered_set<std::string> liveLights;
    for (const FlatNode& node : flat_.lights)
      if (placeLight(node, backend, hooks)) liveLights.insert(node.key());
    eraseExcept(lights_, liveLights, [&](auto id) { backend.removeLight(id); });
  }

  // Moves the instances and lights below transforms whose matrix changed,
  // and re-places lights whose own fields changed.
  void moveEdited(const sg::Scene& scene, const sg::MergedChanges& changes, BackendScene& backend, const Hooks& hooks) {
    std::unordered_set<std::uint32_t> instances, lights;
    for (const auto& [id, e] : changes.entries()) {
      if (e.type == sg::ContainerType::Transform && e.changed(sg::Transform::Matrix)) {
        if (auto it = flat_.instancesUnder.find(id); it != flat_.instancesUnder.end())
          instances.insert(it->second.begin(), it->second.end());
        if (auto it = flat_.lightsUnder.find(id); it != flat_.lightsUnder.end())
          lights.insert(it->second.begin(), it->second.end());
      }
      if (e.type == sg::ContainerType::Light && !e.destroyed)
        for (std::uint32_t i = 0; i < flat_.lights.size(); ++i)
          if (flat_.lights[i].id == id) lights.insert(i);
    }
    for (std::uint32_t i : instances) {
      FlatNode& node = flat_.instances[i];
      node.world = worldMatrix(scene, node.path);
      auto placed = instances_.find(node.key());
      if (placed == instances_.end()) continue;  // not rendered here
      backend.setInstanceTransform(placed->second.id, node.world);
      placed->second.world = node.world;
      ++transformUpdates;
    }
    for (std::uint32_t i : lights) {
      FlatNode& node = flat_.lights[i];
      node.world = worldMatrix(scene, node.path);
      placeLight(node, backend, hooks);
    }
  }

  std::unordered_map<std::string, Placed>& instances() { return instances_; }
  const std::unordered_map<std::string, Placed>& instances() const { return instances_; }
  const FlatScene& flat() const { return flat_; }

  std::uint64_t flattenings = 0;
  std::uint64_t transformUpdates = 0;

 private:
  bool placeLight(const FlatNode& node, BackendScene& backend, const Hooks& hooks) {
    auto light = hooks.light(node);
    if (!light) return false;
    auto held = lights_.find(node.key());
    if (held == lights_.end())
      lights_.emplace(node.key(), backend.addLight(*light));
    else
      backend.setLight(held->second, *light);
    return true;
  }

  template <class Map, class Remove>
  static void eraseExcept(Map& map, const std::unordered_set<std::string>& keep, Remove remove) {
    for (auto it = map.begin(); it != map.end();) {
      if (keep.count(it->first)) {
        ++it;
        continue;
      }
      remove(it->second);
      it = map.erase(it);
    }
  }

  FlatScene flat_;
  std::unordered_map<std::string, Placed> instances_;
  std::unordered_map<std::string, typename Types::LightId> lights_;
};

}  // namespace tsr::med
