#pragma once

#include "tsr/cov/id_renderer.hpp"

#include <memory>

namespace tsr::cov {

struct EmbreeIdSettings {
  int threads = 0;              // 0 = all hardware threads
  std::uint32_t tileSize = 32;  // pixels per tile side; tiles are the unit of parallel work
};

// The id pass as Embree 3 primary rays: one Embree scene per mesh, instanced
// into a top-level scene, so moving an instance only rebuilds the top level
// (Embree 3 cannot refit instance levels) and a mesh is built once however
// often it is placed. Rays go out in packets of 4x4 pixels (rtcIntersect16)
// over tiles in parallel.
class EmbreeIdRenderer final : public IdRenderer {
 public:
  explicit EmbreeIdRenderer(EmbreeIdSettings settings = {});
  ~EmbreeIdRenderer() override;
  EmbreeIdRenderer(const EmbreeIdRenderer&) = delete;
  EmbreeIdRenderer& operator=(const EmbreeIdRenderer&) = delete;

  void setSettings(const EmbreeIdSettings& settings);
  const EmbreeIdSettings& settings() const;

  MeshId addMesh(MeshData data) override;
  void setMeshData(MeshId mesh, MeshData data) override;
  void updateMeshVertices(MeshId mesh, const VertexEdit& edit) override;
  void removeMesh(MeshId mesh) override;

  InstanceId addInstance(const Instance& instance) override;
  void setInstanceTransform(InstanceId instance, const glm::mat4& transform) override;
  void setInstanceObject(InstanceId instance, ObjectId object) override;
  void setInstanceTransparent(InstanceId instance, bool transparent) override;
  void removeInstance(InstanceId instance) override;

  std::size_t meshCount() const override;
  std::size_t instanceCount() const override;

  IdBuffer render(const Camera& camera, const Region& region) override;

  // Commits pending edits to Embree (render() does it too); idempotent.
  void commit();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace tsr::cov
