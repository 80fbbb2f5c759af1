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
#include "tsr/med/scene_adapter.hpp"
#include "tsr/med/scene_flattening.hpp"

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
  const Counters& counters() const { return counters_; }

 protected:
  void convert(const sg::Scene& scene) override;
  void sync(const sg::Scene& scene, const sg::MergedChanges& changes) override;

 private:
  struct PlacedInstance {
    embree::InstanceId id;
    sg::ContainerId geometry;
    glm::mat4 world;
    embree::MaterialId material;
  };

  void syncTextures(const sg::Scene& scene, const sg::MergedChanges& changes);
  void syncMaterials(const sg::Scene& scene, const sg::MergedChanges& changes);
  bool syncMeshes(const sg::Scene& scene, const sg::MergedChanges& changes);  // true: placement must be redone
  void syncTransforms(const sg::Scene& scene, const sg::MergedChanges& changes);
  void place(const sg::Scene& scene);  // flatten and diff instances and lights
  void dropUnused(const sg::Scene& scene);

  std::optional<embree::MeshId> meshFor(const sg::Scene& scene, sg::ContainerId geometry);
  embree::MaterialId materialFor(const sg::Scene& scene, sg::ContainerId material);
  std::optional<embree::TextureId> textureFor(const sg::Scene& scene, sg::ContainerId image);
  embree::MaterialId materialOfGeometry(const sg::Scene& scene, sg::ContainerId geometry);
  void placeLight(const sg::Scene& scene, const FlatNode& node);

  std::shared_ptr<embree::Device> device_;
  sg::ContainerId root_, background_;
  std::unique_ptr<embree::Scene> scene_;
  FlatScene flat_;
  std::unordered_map<sg::ContainerId, embree::MeshId> meshes_;
  std::unordered_set<sg::ContainerId> unrenderable_;  // invalid or empty geometry, skipped
  std::unordered_map<sg::ContainerId, embree::MaterialId> materials_;  // kNoContainer: the default
  std::unordered_map<sg::ContainerId, embree::TextureId> textures_;
  std::unordered_map<std::string, PlacedInstance> instances_;  // by flattened path key
  std::unordered_map<std::string, embree::LightId> lights_;
  Counters counters_;
};

}  // namespace tsr::med::embree_mediator
