#pragma once
// Keeps a Vulkan back-end scene in step with a replica, the way the Embree
// mediator does: sync runs in phases — textures, materials, meshes,
// placement (instances and lights), environment — each guarded by what the
// merged changes name. A moved transform rewrites only the instance records
// below it; a ranged vertex edit uploads only that range.
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "tsr/med/instance_placement.hpp"
#include "tsr/med/scene_adapter.hpp"
#include "tsr/vk/scene.hpp"

namespace tsr::med::vulkan_mediator {

class VulkanSceneAdapter final : public SceneAdapter {
 public:
  // What the adapter has done, for tests of incremental sync.
  struct Counters {
    std::uint64_t meshBuilds = 0;        // whole meshes handed to the back-end
    std::uint64_t meshRangeUpdates = 0;  // vertex ranges uploaded
    std::uint64_t instanceTransforms = 0;
    std::uint64_t materialUpdates = 0;
    std::uint64_t flattenings = 0;
  };

  VulkanSceneAdapter(std::shared_ptr<vk::Device> device, sg::ContainerId root, sg::ContainerId background);

  vk::Scene& scene() { return *scene_; }
  bool converted() const { return scene_ != nullptr; }
  const vk::Environment& environment() const { return environment_; }
  Counters counters() const;

 protected:
  void convert(const sg::Scene& scene) override;
  void sync(const sg::Scene& scene, const sg::MergedChanges& changes) override;

 private:
  struct Types {
    using Scene = vk::Scene;
    using MeshId = vk::MeshId;
    using MaterialId = vk::MaterialId;
    using InstanceId = vk::InstanceId;
    using LightId = vk::LightId;
    using Light = vk::Light;
  };

  void syncTextures(const sg::Scene& scene, const sg::MergedChanges& changes);
  void syncMaterials(const sg::Scene& scene, const sg::MergedChanges& changes);
  bool syncMeshes(const sg::Scene& scene, const sg::MergedChanges& changes);  // true: placement must be redone
  void dropMeshes(const std::unordered_set<sg::ContainerId>& geometries);
  InstancePlacement<Types>::Hooks hooks(const sg::Scene& scene);
  void setEnvironment(const sg::Scene& scene);
  void dropUnused(const sg::Scene& scene);

  std::optional<vk::MeshId> meshFor(const sg::Scene& scene, sg::ContainerId geometry);
  vk::MaterialId materialFor(const sg::Scene& scene, sg::ContainerId material);
  vk::MaterialId materialOfGeometry(const sg::Scene& scene, sg::ContainerId geometry);
  std::optional<vk::TextureId> textureFor(const sg::Scene& scene, sg::ContainerId image);

  std::shared_ptr<vk::Device> device_;
  sg::ContainerId root_, background_;
  std::unique_ptr<vk::Scene> scene_;
  vk::Environment environment_;
  InstancePlacement<Types> placement_;
  std::unordered_map<sg::ContainerId, vk::MeshId> meshes_;
  std::unordered_set<sg::ContainerId> unrenderable_;  // invalid or empty geometry, skipped
  std::unordered_map<sg::ContainerId, vk::MaterialId> materials_;  // kNoContainer: the default
  std::unordered_map<sg::ContainerId, vk::TextureId> textures_;
  Counters counters_;
};

}  // namespace tsr::med::vulkan_mediator
