#pragma once
// Keeps an id pass's scene in step with a replica. Sync runs in phases —
// meshes, placement (instances), transparency, transforms — each guarded by
// what the merged changes name, so a moved transform updates only the
// instance matrices below it and a material edit only the transparency of
// the instances that use it.
#include <functional>
#include <memory>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "tsr/cov/id_renderer.hpp"
#include "tsr/med/scene_adapter.hpp"
#include "tsr/med/scene_flattening.hpp"

namespace tsr::med::coverage_mediator {

class CoverageSceneAdapter final : public SceneAdapter {
 public:
  // Makes an empty back-end scene; called for every conversion.
  using RendererFactory = std::function<std::unique_ptr<cov::IdRenderer>()>;

  // What the adapter has done, for tests and benchmarks of incremental sync.
  struct Counters {
    std::uint64_t meshBuilds = 0;        // whole meshes handed to the back-end
    std::uint64_t meshRangeUpdates = 0;  // vertex ranges updated in place
    std::uint64_t instanceTransforms = 0;
    std::uint64_t transparencyUpdates = 0;
    std::uint64_t flattenings = 0;
  };

  CoverageSceneAdapter(RendererFactory make, sg::ContainerId root);

  cov::IdRenderer& renderer() { return *renderer_; }
  const Counters& counters() const { return counters_; }

 protected:
  void convert(const sg::Scene& scene) override;
  void sync(const sg::Scene& scene, const sg::MergedChanges& changes) override;

 private:
  struct PlacedInstance {
    cov::InstanceId id;
    sg::ContainerId geometry;
    glm::mat4 world;
    bool transparent;
  };

  bool syncMeshes(const sg::Scene& scene, const sg::MergedChanges& changes);  // true: placement must be redone
  void syncTransparency(const sg::Scene& scene, const sg::MergedChanges& changes);
  void syncTransforms(const sg::Scene& scene, const sg::MergedChanges& changes);
  void place(const sg::Scene& scene);  // flatten and diff instances
  void dropUnusedMeshes(const sg::Scene& scene);
  void removeInstancesOf(const std::unordered_set<sg::ContainerId>& geometries);

  std::optional<cov::MeshId> meshFor(const sg::Scene& scene, sg::ContainerId geometry);
  bool transparentGeometry(const sg::Scene& scene, sg::ContainerId geometry) const;

  RendererFactory make_;
  sg::ContainerId root_;
  std::unique_ptr<cov::IdRenderer> renderer_;
  FlatScene flat_;
  std::unordered_map<sg::ContainerId, cov::MeshId> meshes_;
  std::unordered_set<sg::ContainerId> unrenderable_;  // invalid or empty geometry, skipped
  std::unordered_map<std::string, PlacedInstance> instances_;  // by flattened path key
  Counters counters_;
};

}  // namespace tsr::med::coverage_mediator
