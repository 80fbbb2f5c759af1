#pragma once

#include <vulkan/vulkan.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace tsr::vk {

struct DeviceOptions {
  // Enable VK_LAYER_KHRONOS_validation with a messenger that counts (and logs)
  // errors and warnings. Throws Error if the layer is not installed.
  bool validation = false;
  // Pick the first physical device whose name contains this; empty: the
  // first device with Vulkan 1.3 and a graphics queue.
  std::string deviceNameContains{};
  // For presentation: instance extensions a window system needs (e.g. from
  // glfwGetRequiredInstanceExtensions). Non-empty also enables VK_KHR_swapchain.
  std::vector<std::string> instanceExtensions{};

  // Options for presenting with SwapchainTarget: instanceExtensions from
  // glfwGetRequiredInstanceExtensions. glfwInit() must have succeeded;
  // throws Error if GLFW finds no Vulkan support. (Defined in
  // swapchain_target.cpp; headless code never calls into GLFW.)
  static DeviceOptions forWindows(bool validation = false);
};

// Owns the Vulkan instance, the chosen physical device, the logical device,
// one graphics queue and a command pool for one-shot uploads. Scenes and
// renderers share it through std::shared_ptr. Not thread-safe.
class Device {
 public:
  static std::shared_ptr<Device> create(const DeviceOptions& options = {});
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  // True if VK_LAYER_KHRONOS_validation can be enabled on this machine.
  static bool validationLayerAvailable();

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physical_; }
  VkDevice handle() const { return device_; }
  VkQueue queue() const { return queue_; }
  std::uint32_t queueFamily() const { return queueFamily_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  std::string name() const { return properties_.deviceName; }
  bool presentationEnabled() const { return presentation_; }
  // Several indirect draws in one call: guided rendering needs it.
  bool multiDrawIndirect() const { return multiDrawIndirect_; }
  // Needed to draw see-through volumes (they are skipped without it).
  bool dualSourceBlend() const { return dualSourceBlend_; }
  // The vertex format of compact positions: three 16-bit fractions where
  // the device reads that from vertex buffers (6 bytes), else four, the
  // fourth unused (8 bytes).
  VkFormat positionFormat() const { return positionFormat_; }
  std::uint32_t positionBytes() const { return positionFormat_ == VK_FORMAT_R16G16B16_UNORM ? 6 : 8; }

  // Memory type index with all `required` flags among `typeBits`; throws if none.
  std::uint32_t memoryType(std::uint32_t typeBits, VkMemoryPropertyFlags required) const;

  // Records with `record` into a fresh command buffer, submits and waits.
  void submitAndWait(const std::function<void(VkCommandBuffer)>& record) const;

  // Validation messages seen since creation (zero without validation).
  std::uint64_t validationErrors() const { return errors_.load(); }
  std::uint64_t validationWarnings() const { return warnings_.load(); }
  std::vector<std::string> validationMessages() const;

 private:
  Device() = default;
  static VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                  VkDebugUtilsMessageTypeFlagsEXT types,
                                                  const VkDebugUtilsMessengerCallbackDataEXT* data, void* self);

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  std::uint32_t queueFamily_ = 0;
  VkCommandPool uploadPool_ = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  bool presentation_ = false;
  bool multiDrawIndirect_ = false;
  bool dualSourceBlend_ = false;
  VkFormat positionFormat_ = VK_FORMAT_R16G16B16A16_UNORM;
  std::atomic<std::uint64_t> errors_{0};
  std::atomic<std::uint64_t> warnings_{0};
  mutable std::mutex messagesMutex_;
  std::vector<std::string> messages_;
};

}  // namespace tsr::vk
