#include "tsr/vk/swapchain_target.hpp"

#include "resources/buffer.hpp"
#include "resources/image.hpp"
#include "tsr/vk/error.hpp"
#include "vk_struct.hpp"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace tsr::vk {

DeviceOptions DeviceOptions::forWindows(bool validation) {
  std::uint32_t count = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&count);
  if (!names || count == 0) {
    const char* why = nullptr;
    glfwGetError(&why);
    throw Error(std::string("glfwGetRequiredInstanceExtensions: no Vulkan presentation support") +
                (why ? std::string(" (") + why + ")" : std::string(" (was glfwInit called?)")));
  }
  DeviceOptions options;
  options.validation = validation;
  for (std::uint32_t i = 0; i < count; ++i) options.instanceExtensions.emplace_back(names[i]);
  return options;
}

namespace {

constexpr std::uint64_t kNoTimeout = std::numeric_limits<std::uint64_t>::max();

std::uint8_t encodeSrgb(float linear) {
  if (!(linear > 0.0f)) return 0;  // also NaN
  if (linear >= 1.0f) return 255;
  float s = linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
  return std::uint8_t(std::lround(std::clamp(s, 0.0f, 1.0f) * 255.0f));
}

bool isBgra(VkFormat f) { return f == VK_FORMAT_B8G8R8A8_SRGB || f == VK_FORMAT_B8G8R8A8_UNORM; }

}  // namespace

struct SwapchainTarget::Impl {
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  VkSwapchainKHR swapchain = VK_NULL_HANDLE;
  std::vector<VkImage> images;
  std::vector<VkSemaphore> renderDone;  // one per swapchain image, waited on by present
  VkSemaphore imageAvailable = VK_NULL_HANDLE;
  VkFence inFlight = VK_NULL_HANDLE;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  Buffer staging;
  Buffer readback;
  VkColorSpaceKHR colourSpace = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
  bool needsRecreate = false;
};

SwapchainTarget::SwapchainTarget(std::shared_ptr<Device> device, GLFWwindow* window, SwapchainOptions options)
    : device_(std::move(device)), window_(window), options_(options), impl_(std::make_unique<Impl>()) {
  if (!device_) throw Error("SwapchainTarget: null device");
  if (!window_) throw Error("SwapchainTarget: null window");
  if (!device_->presentationEnabled())
    throw Error("SwapchainTarget: the device was created without window extensions (use DeviceOptions::forWindows())");
  if (glfwGetWindowAttrib(window_, GLFW_CLIENT_API) != GLFW_NO_API)
    throw Error("SwapchainTarget: the window must be created with GLFW_CLIENT_API = GLFW_NO_API");

  VkDevice dev = device_->handle();
  try {
    check(glfwCreateWindowSurface(device_->instance(), window_, nullptr, &impl_->surface), "glfwCreateWindowSurface");
    VkBool32 supported = VK_FALSE;
    check(vkGetPhysicalDeviceSurfaceSupportKHR(device_->physicalDevice(), device_->queueFamily(), impl_->surface,
                                               &supported),
          "vkGetPhysicalDeviceSurfaceSupportKHR");
    if (!supported) throw Error("SwapchainTarget: the device's graphics queue cannot present to this window");

    VkSemaphoreCreateInfo sci = vkStruct<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
    check(vkCreateSemaphore(dev, &sci, nullptr, &impl_->imageAvailable), "vkCreateSemaphore");
    VkFenceCreateInfo fci = vkStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    fci.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    check(vkCreateFence(dev, &fci, nullptr, &impl_->inFlight), "vkCreateFence");
    VkCommandPoolCreateInfo pci = vkStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pci.queueFamilyIndex = device_->queueFamily();
    check(vkCreateCommandPool(dev, &pci, nullptr, &impl_->pool), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo ai =
        vkStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    ai.commandPool = impl_->pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    check(vkAllocateCommandBuffers(dev, &ai, &impl_->cmd), "vkAllocateCommandBuffers");

    createSwapchain();
  } catch (...) {
    destroySwapchainResources();
    if (impl_->pool) vkDestroyCommandPool(dev, impl_->pool, nullptr);
    if (impl_->inFlight) vkDestroyFence(dev, impl_->inFlight, nullptr);
    if (impl_->imageAvailable) vkDestroySemaphore(dev, impl_->imageAvailable, nullptr);
    if (impl_->surface) vkDestroySurfaceKHR(device_->instance(), impl_->surface, nullptr);
    throw;
  }
}

SwapchainTarget::~SwapchainTarget() {
  VkDevice dev = device_->handle();
  vkDeviceWaitIdle(dev);
  destroySwapchainResources();
  vkDestroyCommandPool(dev, impl_->pool, nullptr);
  vkDestroyFence(dev, impl_->inFlight, nullptr);
  vkDestroySemaphore(dev, impl_->imageAvailable, nullptr);
  vkDestroySurfaceKHR(device_->instance(), impl_->surface, nullptr);
}

void SwapchainTarget::destroySwapchainResources() {
  VkDevice dev = device_->handle();
  if (options_.overlay && !impl_->images.empty()) options_.overlay->swapchainChanged(format_, {0, 0}, {});
  for (VkSemaphore s : impl_->renderDone) vkDestroySemaphore(dev, s, nullptr);
  impl_->renderDone.clear();
  impl_->images.clear();
  if (impl_->swapchain) vkDestroySwapchainKHR(dev, impl_->swapchain, nullptr);
  impl_->swapchain = VK_NULL_HANDLE;
}

// (Re)creates the swapchain at the surface's current size; extent_ stays
// 0 x 0 (and no swapchain exists) while the window is minimised.
void SwapchainTarget::createSwapchain() {
  VkDevice dev = device_->handle();
  VkPhysicalDevice phys = device_->physicalDevice();
  vkDeviceWaitIdle(dev);

  VkSurfaceCapabilitiesKHR caps;
  check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(phys, impl_->surface, &caps),
        "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
  VkExtent2D extent = caps.currentExtent;
  if (extent.width == 0xFFFFFFFFu) {  // the surface follows the swapchain: use the window's size
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    extent.width = std::clamp(std::uint32_t(std::max(w, 0)), caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(std::uint32_t(std::max(h, 0)), caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  if (extent.width == 0 || extent.height == 0) {
    destroySwapchainResources();
    extent_ = {0, 0};
    impl_->needsRecreate = true;
    return;
  }

  VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  if (options_.readback) usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  if (options_.overlay) usage |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  if ((caps.supportedUsageFlags & usage) != usage)
    throw Error(std::string("SwapchainTarget: the surface does not allow transfer ") +
                (options_.readback ? "to and from" : "into") + " its images" +
                (options_.overlay ? " or drawing to them (for the overlay)" : ""));

  if (format_ == VK_FORMAT_UNDEFINED) {
    std::uint32_t count = 0;
    check(vkGetPhysicalDeviceSurfaceFormatsKHR(phys, impl_->surface, &count, nullptr),
          "vkGetPhysicalDeviceSurfaceFormatsKHR");
    std::vector<VkSurfaceFormatKHR> formats(count);
    check(vkGetPhysicalDeviceSurfaceFormatsKHR(phys, impl_->surface, &count, formats.data()),
          "vkGetPhysicalDeviceSurfaceFormatsKHR");
    // The bytes written are sRGB-encoded either way; a copy does no conversion.
    for (VkFormat want :
         {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_R8G8B8A8_UNORM}) {
      for (const auto& f : formats)
        if (f.format == want && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) {
          format_ = f.format;
          impl_->colourSpace = f.colorSpace;
          break;
        }
      if (format_ != VK_FORMAT_UNDEFINED) break;
    }
    if (format_ == VK_FORMAT_UNDEFINED)
      throw Error("SwapchainTarget: the surface offers no 8-bit BGRA/RGBA sRGB format");
  }

  std::uint32_t imageCount = caps.minImageCount + 1;
  if (caps.maxImageCount > 0) imageCount = std::min(imageCount, caps.maxImageCount);

  VkSwapchainCreateInfoKHR ci = vkStruct<VkSwapchainCreateInfoKHR>(VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR);
  ci.surface = impl_->surface;
  ci.minImageCount = imageCount;
  ci.imageFormat = format_;
  ci.imageColorSpace = impl_->colourSpace;
  ci.imageExtent = extent;
  ci.imageArrayLayers = 1;
  ci.imageUsage = usage;
  ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.preTransform = (caps.supportedTransforms & VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR)
                        ? VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR
                        : caps.currentTransform;
  ci.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  for (VkCompositeAlphaFlagBitsKHR a :
       {VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR, VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR,
        VK_COMPOSITE_ALPHA_PRE_MULTIPLIED_BIT_KHR, VK_COMPOSITE_ALPHA_POST_MULTIPLIED_BIT_KHR})
    if (caps.supportedCompositeAlpha & a) {
      ci.compositeAlpha = a;
      break;
    }
  ci.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // always supported
  ci.clipped = VK_TRUE;
  VkSwapchainKHR old = impl_->swapchain;
  ci.oldSwapchain = old;

  VkSwapchainKHR created = VK_NULL_HANDLE;
  check(vkCreateSwapchainKHR(dev, &ci, nullptr, &created), "vkCreateSwapchainKHR");
  destroySwapchainResources();  // the old one (retired by the create above) and its semaphores
  impl_->swapchain = created;
  extent_ = extent;
  ++generation_;
  impl_->needsRecreate = false;

  std::uint32_t count = 0;
  check(vkGetSwapchainImagesKHR(dev, created, &count, nullptr), "vkGetSwapchainImagesKHR");
  impl_->images.resize(count);
  check(vkGetSwapchainImagesKHR(dev, created, &count, impl_->images.data()), "vkGetSwapchainImagesKHR");
  VkSemaphoreCreateInfo sci = vkStruct<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
  impl_->renderDone.assign(count, VK_NULL_HANDLE);
  for (auto& s : impl_->renderDone) check(vkCreateSemaphore(dev, &sci, nullptr, &s), "vkCreateSemaphore");
  if (options_.overlay) options_.overlay->swapchainChanged(format_, extent, impl_->images);

  if (options_.readback) {
    VkDeviceSize bytes = VkDeviceSize(extent.width) * extent.height * 4;
    if (impl_->readback.size() != bytes)
      impl_->readback = Buffer(*device_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, Buffer::kHost);
  }
  spdlog::debug("tsr::vk: swapchain {}x{}, {} images, format {}", extent.width, extent.height, count, int(format_));
}

std::vector<std::uint8_t> SwapchainTarget::encode(const FrameBuffer& fb) const { return encode(fb.colourImage()); }

std::vector<std::uint8_t> SwapchainTarget::encode(const std::vector<glm::vec4>& colour) const {
  const bool bgra = isBgra(format_);
  std::vector<std::uint8_t> out(colour.size() * 4);
  for (std::size_t i = 0; i < colour.size(); ++i) {
    std::uint8_t r = encodeSrgb(colour[i].r), g = encodeSrgb(colour[i].g), b = encodeSrgb(colour[i].b);
    out[4 * i + 0] = bgra ? b : r;
    out[4 * i + 1] = g;
    out[4 * i + 2] = bgra ? r : b;
    out[4 * i + 3] = 255;
  }
  return out;
}

namespace {

// Records the image cleared to black and the staged pixels (width x
// height, cut to the swapchain's extent) copied into it.
void recordUpload(VkCommandBuffer cmd, VkImage image, VkBuffer staging, std::uint32_t width, std::uint32_t height,
                  VkExtent2D extent) {
  // The semaphore wait is at the transfer stage, so the transition may start there.
  imageBarrier(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
  VkClearColorValue black{};
  black.float32[3] = 1.0f;
  VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdClearColorImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &all);
  const std::uint32_t w = std::min(width, extent.width), h = std::min(height, extent.height);
  if (w > 0 && h > 0) {
    imageBarrier(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    VkBufferImageCopy copy{};
    copy.bufferRowLength = width;
    copy.bufferImageHeight = height;
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {w, h, 1};
    vkCmdCopyBufferToImage(cmd, staging, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
  }
}

// Records the presented image copied into the host-visible readback buffer,
// then handed to presentation.
void recordReadback(VkCommandBuffer cmd, VkImage image, VkBuffer readback, VkExtent2D extent) {
  imageBarrier(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
               VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {extent.width, extent.height, 1};
  vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback, 1, &copy);
  VkMemoryBarrier toHost = vkStruct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
  toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0, nullptr, 0,
                       nullptr);
  imageBarrier(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
               VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT,
               0);
}

}  // namespace

bool SwapchainTarget::present(const FrameBuffer& fb) { return present(fb.width(), fb.height(), fb.colourImage()); }

bool SwapchainTarget::present(std::uint32_t width, std::uint32_t height, const std::vector<glm::vec4>& colour) {
  if (colour.size() != std::size_t(width) * height)
    throw Error("SwapchainTarget::present: " + std::to_string(colour.size()) + " pixels for a " +
                std::to_string(width) + "x" + std::to_string(height) + " image");
  VkDevice dev = device_->handle();

  // Follow the window's size even where the platform does not report
  // VK_ERROR_OUT_OF_DATE_KHR on resize.
  VkSurfaceCapabilitiesKHR caps;
  check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(device_->physicalDevice(), impl_->surface, &caps),
        "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
  if (caps.currentExtent.width != 0xFFFFFFFFu &&
      (caps.currentExtent.width != extent_.width || caps.currentExtent.height != extent_.height))
    impl_->needsRecreate = true;
  if (impl_->needsRecreate) createSwapchain();
  if (!impl_->swapchain) return false;  // minimised

  check(vkWaitForFences(dev, 1, &impl_->inFlight, VK_TRUE, kNoTimeout), "vkWaitForFences");

  std::uint32_t index = 0;
  VkResult acquired = VK_ERROR_OUT_OF_DATE_KHR;
  for (int attempt = 0; attempt < 3 && acquired == VK_ERROR_OUT_OF_DATE_KHR; ++attempt) {
    if (attempt > 0) {
      createSwapchain();
      if (!impl_->swapchain) return false;
    }
    acquired = vkAcquireNextImageKHR(dev, impl_->swapchain, kNoTimeout, impl_->imageAvailable, VK_NULL_HANDLE, &index);
  }
  if (acquired == VK_SUBOPTIMAL_KHR)
    impl_->needsRecreate = true;  // the semaphore is signalled: present this one, recreate next time
  else
    check(acquired, "vkAcquireNextImageKHR");

  // Stage the encoded pixels (the buffer is idle: the fence above waited for its last use).
  const std::vector<std::uint8_t> pixels = encode(colour);
  if (!pixels.empty()) {
    if (impl_->staging.size() < pixels.size())
      impl_->staging = Buffer(*device_, pixels.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, Buffer::kHost);
    std::memcpy(impl_->staging.mapped(), pixels.data(), pixels.size());
  }

  VkImage image = impl_->images[index];
  VkCommandBuffer cmd = impl_->cmd;
  check(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo bi = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");

  recordUpload(cmd, image, impl_->staging.handle(), width, height, extent_);
  if (options_.overlay) options_.overlay->record(cmd, index);
  if (options_.readback) {
    recordReadback(cmd, image, impl_->readback.handle(), extent_);
  } else {
    imageBarrier(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0);
  }
  check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");

  check(vkResetFences(dev, 1, &impl_->inFlight), "vkResetFences");
  VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
  VkSubmitInfo si = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
  si.waitSemaphoreCount = 1;
  si.pWaitSemaphores = &impl_->imageAvailable;
  si.pWaitDstStageMask = &waitStage;
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  si.signalSemaphoreCount = 1;
  si.pSignalSemaphores = &impl_->renderDone[index];
  check(vkQueueSubmit(device_->queue(), 1, &si, impl_->inFlight), "vkQueueSubmit");

  VkPresentInfoKHR pi = vkStruct<VkPresentInfoKHR>(VK_STRUCTURE_TYPE_PRESENT_INFO_KHR);
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = &impl_->renderDone[index];
  pi.swapchainCount = 1;
  pi.pSwapchains = &impl_->swapchain;
  pi.pImageIndices = &index;
  VkResult presentedResult = vkQueuePresentKHR(device_->queue(), &pi);

  // One frame in flight: wait for the copy, so the staging buffer and the
  // command buffer are free and the readback is complete.
  check(vkWaitForFences(dev, 1, &impl_->inFlight, VK_TRUE, kNoTimeout), "vkWaitForFences");
  if (options_.readback) {
    const auto* bytes = static_cast<const std::uint8_t*>(impl_->readback.mapped());
    lastPixels_.assign(bytes, bytes + std::size_t(extent_.width) * extent_.height * 4);
    lastWidth_ = extent_.width;
    lastHeight_ = extent_.height;
  }

  if (presentedResult == VK_ERROR_OUT_OF_DATE_KHR || presentedResult == VK_SUBOPTIMAL_KHR) {
    impl_->needsRecreate = true;
    if (presentedResult == VK_ERROR_OUT_OF_DATE_KHR) return false;  // the image was not shown
  } else {
    check(presentedResult, "vkQueuePresentKHR");
  }
  ++presented_;
  return true;
}

}  // namespace tsr::vk
