#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

namespace tsr::vk {

// Draws over what SwapchainTarget::present copied into a swapchain image (a
// user interface, say), in the same command buffer, before presentation.
// The overlay owns whatever it needs to draw (render pass, image views,
// pipelines); the target only tells it the images and hands it the moment.
class SwapchainOverlay {
 public:
  virtual ~SwapchainOverlay() = default;

  // After every swapchain (re)creation, with its images (created with
  // COLOR_ATTACHMENT usage), their format and size; and with no images
  // before those are destroyed, so the overlay frees what refers to them.
  // The device is idle at both times.
  virtual void swapchainChanged(VkFormat format, VkExtent2D extent, const std::vector<VkImage>& images) = 0;

  // Records the drawing over images[index]. The image arrives in
  // TRANSFER_DST_OPTIMAL after transfer writes, and must be left in
  // TRANSFER_DST_OPTIMAL with the overlay's writes available to the
  // transfer stage (a render pass whose attachment starts and ends in that
  // layout, with external dependencies on the transfer stage, does both).
  virtual void record(VkCommandBuffer cmd, std::uint32_t index) = 0;
};

}  // namespace tsr::vk
