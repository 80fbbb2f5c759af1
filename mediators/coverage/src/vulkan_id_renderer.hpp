#pragma once
// The coverage id pass on the Vulkan rasterizer: backends/coverage's
// IdRenderer interface implemented with tsr_vulkan's Renderer::renderIds.
//
// Layering: this is the one place where the coverage mediator uses a second
// back-end library (tsr_vulkan) besides its own (tsr_coverage). It lives in
// the mediator, not in backends/coverage, so back-ends stay independent of
// each other; the viewport parameter engine=vulkan selects it.
#include <memory>
#include <unordered_map>

#include "tsr/cov/id_renderer.hpp"

namespace tsr::med::coverage_mediator {

class VulkanIdRenderer final : public cov::IdRenderer {
 public:
  VulkanIdRenderer();
  ~VulkanIdRenderer() override;
  VulkanIdRenderer(const VulkanIdRenderer&) = delete;
  VulkanIdRenderer& operator=(const VulkanIdRenderer&) = delete;

  cov::MeshId addMesh(cov::MeshData data) override;
  void setMeshData(cov::MeshId mesh, cov::MeshData data) override;
  void updateMeshVertices(cov::MeshId mesh, const cov::VertexEdit& edit) override;
  void removeMesh(cov::MeshId mesh) override;

  cov::InstanceId addInstance(const cov::Instance& instance) override;
  void setInstanceTransform(cov::InstanceId instance, const glm::mat4& transform) override;
  void setInstanceObject(cov::InstanceId instance, cov::ObjectId object) override;
  void setInstanceTransparent(cov::InstanceId instance, bool transparent) override;
  void removeInstance(cov::InstanceId instance) override;

  std::size_t meshCount() const override;
  std::size_t instanceCount() const override;

  // The rasterizer clips at a far plane: near * 1e7 here.
  cov::IdBuffer render(const cov::Camera& camera, const cov::Region& region) override;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace tsr::med::coverage_mediator
