#pragma once
// Keeps an Embree back-end scene in step with a replica. Sync runs in
// phases — textures, materials, meshes, placement (instances and lights),
// environment — each guarded by what the merged changes name, so a moved
// transform updates only the instance matrices below it.
#include <memory>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "tsr/embree/scene.hpp"
#include "tsr/med/instance_placement.hpp"
#include "tsr/med/scene_adapter.hpp"

namespace tsr::med::embree_mediator {

class EmbreeSceneAdapter final : public SceneAdapter {
 public:
  // What the adapter has done, for tests and benchmarks of incremental sync.
  struct Counters {
    std::uint64_t meshBuilds = 0;        // whole meshes handed to the back-end
    std::uint64_t meshRangeUpdates = 0;  // vertex ranges refitted
    std::uint64_t instanceTransforms = 0;
    std::uint64_t materialUpdates = 0;
    std::uint64_t flattenings = 0;
  };

  EmbreeSceneAdapter(std::shared_ptr<embree::Device> device, sg::ContainerId root, sg::ContainerId background);

  embree::Scene& scene() { return *scene_; }
  Counters counters() const;

 protected:
  void convert(const sg::Scene& scene) override;
  void sync(const sg::Scene& scene, const sg::MergedChanges& changes) override;

 private:
  struct Types {
    using Scene = embree::Scene;
    using MeshId = embree::MeshId;
    using MaterialId = embree::MaterialId;
    using InstanceId = embree::InstanceId;
    using LightId = embree::LightId;
    using Light = embree::Light;
  };

  void syncTextures(const sg::Scene& scene, const sg::MergedChanges& changes);
  void syncMaterials(const sg::Scene& scene, const sg::MergedChanges& changes);
  bool syncMeshes(const sg::Scene& scene, const sg::MergedChanges& changes);  // true: placement must be redone
  InstancePlacement<Types>::Hooks hooks(const sg::Scene& scene);
  void dropUnused(const sg::Scene& scene);

  std::optional<embree::MeshId> meshFor(const sg::Scene& scene, sg::ContainerId geometry);
  embree::MaterialId materialFor(const sg::Scene& scene, sg::ContainerId material);
  std::optional<embree::TextureId> textureFor(const sg::Scene& scene, sg::ContainerId image);
  embree::MaterialId materialOfGeometry(const sg::Scene& scene, sg::ContainerId geometry);

  std::shared_ptr<embree::Device> device_;
  sg::ContainerId root_, background_;
  std::unique_ptr<embree::Scene> scene_;
  InstancePlacement<Types> placement_;
  std::unordered_map<sg::ContainerId, embree::MeshId> meshes_;
  std::unordered_set<sg::ContainerId> unrenderable_;  // invalid or empty geometry, skipped
  std::unordered_map<sg::ContainerId, embree::MaterialId> materials_;  // kNoContainer: the default
  std::unordered_map<sg::ContainerId, embree::TextureId> textures_;
  Counters counters_;
};

}  // namespace tsr::med::embree_mediator
