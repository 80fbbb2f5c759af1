#pragma once

#include "tsr/vk/device.hpp"
#include "tsr/vk/framebuffer.hpp"
#include "tsr/vk/swapchain_overlay.hpp"

#include <vulkan/vulkan.h>

#include <glm/vec4.hpp>

#include <cstdint>
#include <memory>
#include <vector>

struct GLFWwindow;  // GLFW is only touched by SwapchainTarget and DeviceOptions::forWindows

namespace tsr::vk {

struct SwapchainOptions {
  // Also copy every presented image into a host buffer (lastPresentedPixels),
  // for tests. Needs TRANSFER_SRC on swapchain images; throws Error if the
  // surface does not allow it.
  bool readback = false;
  // Drawn over every presented frame (see SwapchainOverlay); must outlive
  // the target. Adds COLOR_ATTACHMENT to the swapchain images' usage.
  SwapchainOverlay* overlay = nullptr;
};

// Presents rendered FrameBuffers in a GLFW window. The window must have been
// created with GLFW_CLIENT_API = GLFW_NO_API and the Device with
// DeviceOptions::forWindows() (the instance extensions GLFW needs, which
// also enables VK_KHR_swapchain). FIFO present mode, B8G8R8A8 (or R8G8B8A8)
// SRGB or UNORM, sRGB-nonlinear colour space.
//
// present() converts the frame buffer's linear colour to sRGB-encoded 8-bit
// (clamped, alpha 255), uploads it through a host-visible staging buffer and
// copies it into the acquired image: the frame buffer's top-left corner goes
// to the window's top-left, what it does not cover is black. The swapchain is
// recreated when the window's size changes or presentation reports
// VK_ERROR_OUT_OF_DATE_KHR / VK_SUBOPTIMAL_KHR. Each present waits for its
// copy to finish (one frame in flight). Not thread-safe; use the Device's
// queue from one thread.
class SwapchainTarget {
 public:
  SwapchainTarget(std::shared_ptr<Device> device, GLFWwindow* window, SwapchainOptions options = {});
  ~SwapchainTarget();
  SwapchainTarget(const SwapchainTarget&) = delete;
  SwapchainTarget& operator=(const SwapchainTarget&) = delete;

  // Presents fb; false if nothing was shown because the window has zero
  // size (minimised). Throws Error on Vulkan failures.
  bool present(const FrameBuffer& fb);
  // The same for a width x height image of linear colour, row 0 at the top
  // (an application's own composition of several renders).
  bool present(std::uint32_t width, std::uint32_t height, const std::vector<glm::vec4>& colour);

  // Current swapchain size (follows the window's framebuffer size).
  std::uint32_t width() const { return extent_.width; }
  std::uint32_t height() const { return extent_.height; }
  VkFormat format() const { return format_; }
  // Swapchains created so far (1 after construction; +1 per recreation).
  std::uint32_t swapchainGeneration() const { return generation_; }
  std::uint64_t framesPresented() const { return presented_; }

  // fb as present() writes it into the image: width*height*4 bytes in this
  // target's channel order (BGRA or RGBA), sRGB-encoded, alpha 255.
  std::vector<std::uint8_t> encode(const FrameBuffer& fb) const;
  std::vector<std::uint8_t> encode(const std::vector<glm::vec4>& colour) const;
  // With readback: the bytes of the image last presented (width() x height()
  // at that time, lastPresentedWidth/Height), else empty.
  const std::vector<std::uint8_t>& lastPresentedPixels() const { return lastPixels_; }
  std::uint32_t lastPresentedWidth() const { return lastWidth_; }
  std::uint32_t lastPresentedHeight() const { return lastHeight_; }

 private:
  struct Impl;
  void createSwapchain();
  void destroySwapchainResources();

  std::shared_ptr<Device> device_;
  GLFWwindow* window_;
  SwapchainOptions options_;
  std::unique_ptr<Impl> impl_;
  VkExtent2D extent_{0, 0};
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  std::uint32_t generation_ = 0;
  std::uint64_t presented_ = 0;
  std::vector<std::uint8_t> lastPixels_;
  std::uint32_t lastWidth_ = 0;
  std::uint32_t lastHeight_ = 0;
};

}  // namespace tsr::vk
