#pragma once
// Dear ImGui drawn over the viewer's swapchain images: the GLFW platform
// backend for input, the Vulkan renderer backend recording into the
// SwapchainTarget's command buffer (vk::SwapchainOverlay).
#include <memory>
#include <vector>

#include "tsr/vk/device.hpp"
#include "tsr/vk/swapchain_overlay.hpp"

struct GLFWwindow;

namespace tsr::app {

class ImGuiOverlay final : public vk::SwapchainOverlay {
 public:
  // Installs ImGui's GLFW callbacks (chaining to those already set).
  ImGuiOverlay(std::shared_ptr<vk::Device> device, GLFWwindow* window);
  ~ImGuiOverlay() override;
  ImGuiOverlay(const ImGuiOverlay&) = delete;
  ImGuiOverlay& operator=(const ImGuiOverlay&) = delete;

  // Starts a frame of widgets; endFrame() closes it for the next present.
  void beginFrame();
  void endFrame();

  void swapchainChanged(VkFormat format, VkExtent2D extent, const std::vector<VkImage>& images) override;
  void record(VkCommandBuffer cmd, std::uint32_t index) override;

 private:
  void initialiseRenderer(VkFormat format, std::uint32_t imageCount);
  void destroyFramebuffers();

  std::shared_ptr<vk::Device> device_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkRenderPass renderPass_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkExtent2D extent_{0, 0};
  std::vector<VkImageView> views_;
  std::vector<VkFramebuffer> framebuffers_;
  bool rendererReady_ = false;
  bool frameReady_ = false;
};

}  // namespace tsr::app
