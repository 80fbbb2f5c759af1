#pragma once
// A viewport rendered by the Vulkan rasterizer. Viewports on one replica
// with the same root and background share a context (one converted scene);
// every context uses the process's one device. Each viewport keeps its own
// renderer, so two viewports may differ in MSAA or shadows.
#include <memory>
#include <mutex>

#include "tsr/med/bounced_light.hpp"
#include "tsr/med/viewport.hpp"
#include "tsr/vk/renderer.hpp"
#include "tsr/vk/shared_device.hpp"
#include "vulkan_scene_adapter.hpp"

namespace tsr::med::vulkan_mediator {

struct VulkanContext {
  std::shared_ptr<vk::SharedDevice> shared;
  VulkanSceneAdapter adapter;
  VulkanContext(const std::shared_ptr<vk::SharedDevice>& s, sg::ContainerId root, sg::ContainerId background)
      : shared(s), adapter(s->device, root, background) {}
};

// The rasterizer's parameters, declared once; registered with it.
const BackendCapabilities& vulkanCapabilities();

class VulkanViewport final : public Viewport {
 public:
  // bouncedLight: what the "bouncedLight" parameter's probes come from; null
  // where no back-end of the build traces it (the ambient term then).
  VulkanViewport(ViewportSettings settings, std::shared_ptr<VulkanContext> context,
                 std::shared_ptr<BouncedLight> bouncedLight = nullptr);
  SceneAdapter::Update synchronize(const sg::Replica& replica) override;
  RenderStats render(const sg::Replica& replica, const View& view, FrameBuffer& out,
                     const RenderControl& control) override;
  const VulkanContext& context() const { return *context_; }
  // The rasterizer's counts for the last frame (triangles and objects drawn); zeros before the first.
  vk::RenderStats lastFrame() const { return renderer_ ? renderer_->lastStats() : vk::RenderStats{}; }
  // Probes of the irradiance volume still to be traced again after the last
  // change, as of the last frame (0: converged, or no volume).
  std::size_t staleProbes() const { return staleProbes_; }

 private:
  vk::RenderSettings renderSettings() const;
  std::shared_ptr<const backend::IrradianceVolume> bouncedLight(const sg::Replica& replica,
                                                                const RenderControl& control, RenderStats& stats);

  std::shared_ptr<VulkanContext> context_;
  std::shared_ptr<BouncedLight> bouncedLight_;
  std::size_t staleProbes_ = 0;
  bool warnedNoBouncedLight_ = false;
  std::unique_ptr<vk::Renderer> renderer_;  // made on first render, like the scene
};

}  // namespace tsr::med::vulkan_mediator
