#include "tsr/vk/device.hpp"

#include "tsr/vk/error.hpp"
#include "vk_struct.hpp"

#include <spdlog/spdlog.h>

#include <cstring>

namespace tsr::vk {

namespace {
constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr std::size_t kKeptMessages = 64;

bool hasExtension(const std::vector<VkExtensionProperties>& list, const char* name) {
  for (const auto& e : list)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

// The device create() runs on, and its graphics queue family.
struct PhysicalChoice {
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  std::uint32_t queueFamily = 0;
  VkPhysicalDeviceProperties properties{};
};

// The first Vulkan 1.3 device with a graphics queue whose name holds
// options.deviceNameContains (and, to present, with the swapchain
// extension); throws naming every device seen when none matches.
PhysicalChoice choosePhysicalDevice(VkInstance instance, const DeviceOptions& options, bool wantSwapchain) {
  PhysicalChoice chosen;
  std::uint32_t count = 0;
  check(vkEnumeratePhysicalDevices(instance, &count, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> physicals(count);
  check(vkEnumeratePhysicalDevices(instance, &count, physicals.data()), "vkEnumeratePhysicalDevices");
  std::string seen;
  for (VkPhysicalDevice p : physicals) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(p, &props);
    seen += std::string(seen.empty() ? "" : ", ") + props.deviceName;
    if (props.apiVersion < VK_API_VERSION_1_3) continue;
    if (!options.deviceNameContains.empty() &&
        std::string(props.deviceName).find(options.deviceNameContains) == std::string::npos)
      continue;
    std::uint32_t extCount = 0;
    vkEnumerateDeviceExtensionProperties(p, nullptr, &extCount, nullptr);
    std::vector<VkExtensionProperties> exts(extCount);
    vkEnumerateDeviceExtensionProperties(p, nullptr, &extCount, exts.data());
    if (wantSwapchain && !hasExtension(exts, VK_KHR_SWAPCHAIN_EXTENSION_NAME)) continue;
    std::uint32_t qCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(p, &qCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(qCount);
    vkGetPhysicalDeviceQueueFamilyProperties(p, &qCount, families.data());
    for (std::uint32_t i = 0; i < qCount; ++i) {
      if (families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) {
        chosen.physical = p;
        chosen.queueFamily = i;
        chosen.properties = props;
        break;
      }
    }
    if (chosen.physical != VK_NULL_HANDLE) break;
  }
  if (chosen.physical == VK_NULL_HANDLE)
    throw Error("no Vulkan 1.3 device with a graphics queue matches (found: " + (seen.empty() ? "none" : seen) + ")");
  return chosen;
}
}  // namespace

bool Device::validationLayerAvailable() {
  std::uint32_t count = 0;
  if (vkEnumerateInstanceLayerProperties(&count, nullptr) != VK_SUCCESS) return false;
  std::vector<VkLayerProperties> layers(count);
  if (vkEnumerateInstanceLayerProperties(&count, layers.data()) != VK_SUCCESS) return false;
  for (const auto& l : layers)
    if (std::strcmp(l.layerName, kValidationLayer) == 0) return true;
  return false;
}

VKAPI_ATTR VkBool32 VKAPI_CALL Device::onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                 VkDebugUtilsMessageTypeFlagsEXT,
                                                 const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  // Called from inside Vulkan calls: never throw, only count and log.
  auto* self = static_cast<Device*>(user);
  const char* text = data && data->pMessage ? data->pMessage : "(no message)";
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
    self->errors_.fetch_add(1);
    spdlog::error("vulkan validation: {}", text);
  } else if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
    self->warnings_.fetch_add(1);
    spdlog::warn("vulkan validation: {}", text);
  } else {
    return VK_FALSE;
  }
  std::lock_guard lock(self->messagesMutex_);
  if (self->messages_.size() < kKeptMessages) self->messages_.emplace_back(text);
  return VK_FALSE;
}

std::vector<std::string> Device::validationMessages() const {
  std::lock_guard lock(messagesMutex_);
  return messages_;
}

std::shared_ptr<Device> Device::create(const DeviceOptions& options) {
  std::shared_ptr<Device> d(new Device());

  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  for (const auto& e : options.instanceExtensions) extensions.push_back(e.c_str());
  if (options.validation) {
    if (!validationLayerAvailable())
      throw Error("validation requested but VK_LAYER_KHRONOS_validation is not installed");
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }

  VkApplicationInfo app = vkStruct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
  app.pApplicationName = "tessera";
  app.pEngineName = "tsr::vk";
  app.apiVersion = VK_API_VERSION_1_3;

  VkDebugUtilsMessengerCreateInfoEXT messenger =
      vkStruct<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
  messenger.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger.pfnUserCallback = &Device::onMessage;
  messenger.pUserData = d.get();

  VkInstanceCreateInfo ici = vkStruct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
  ici.pApplicationInfo = &app;
  ici.enabledLayerCount = std::uint32_t(layers.size());
  ici.ppEnabledLayerNames = layers.data();
  ici.enabledExtensionCount = std::uint32_t(extensions.size());
  ici.ppEnabledExtensionNames = extensions.data();
  if (options.validation) ici.pNext = &messenger;  // also reports instance creation problems
  check(vkCreateInstance(&ici, nullptr, &d->instance_), "vkCreateInstance");

  if (options.validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(d->instance_, "vkCreateDebugUtilsMessengerEXT"));
    if (!create) throw Error("vkCreateDebugUtilsMessengerEXT is not available");
    check(create(d->instance_, &messenger, nullptr, &d->messenger_), "vkCreateDebugUtilsMessengerEXT");
  }

  const bool wantSwapchain = !options.instanceExtensions.empty();
  const PhysicalChoice chosen = choosePhysicalDevice(d->instance_, options, wantSwapchain);
  d->physical_ = chosen.physical;
  d->queueFamily_ = chosen.queueFamily;
  d->properties_ = chosen.properties;
  vkGetPhysicalDeviceMemoryProperties(d->physical_, &d->memory_);
  VkFormatProperties threeHalves{};
  vkGetPhysicalDeviceFormatProperties(d->physical_, VK_FORMAT_R16G16B16_UNORM, &threeHalves);
  if (threeHalves.bufferFeatures & VK_FORMAT_FEATURE_VERTEX_BUFFER_BIT) d->positionFormat_ = VK_FORMAT_R16G16B16_UNORM;

  VkPhysicalDeviceVulkan13Features f13 =
      vkStruct<VkPhysicalDeviceVulkan13Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES);
  VkPhysicalDeviceFeatures2 supported =
      vkStruct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
  supported.pNext = &f13;
  vkGetPhysicalDeviceFeatures2(d->physical_, &supported);
  if (!f13.dynamicRendering) throw Error(std::string(d->properties_.deviceName) + " lacks dynamicRendering");

  VkPhysicalDeviceVulkan13Features enable13 =
      vkStruct<VkPhysicalDeviceVulkan13Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES);
  enable13.dynamicRendering = VK_TRUE;
  VkPhysicalDeviceFeatures2 enable = vkStruct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
  enable.pNext = &enable13;
  enable.features.multiDrawIndirect = supported.features.multiDrawIndirect;
  d->multiDrawIndirect_ = supported.features.multiDrawIndirect == VK_TRUE;
  enable.features.dualSrcBlend = supported.features.dualSrcBlend;
  d->dualSourceBlend_ = supported.features.dualSrcBlend == VK_TRUE;

  float priority = 1.0f;
  VkDeviceQueueCreateInfo qci = vkStruct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
  qci.queueFamilyIndex = d->queueFamily_;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  std::vector<const char*> deviceExtensions;
  if (wantSwapchain) deviceExtensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  VkDeviceCreateInfo dci = vkStruct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
  dci.pNext = &enable;
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  dci.enabledExtensionCount = std::uint32_t(deviceExtensions.size());
  dci.ppEnabledExtensionNames = deviceExtensions.data();
  check(vkCreateDevice(d->physical_, &dci, nullptr, &d->device_), "vkCreateDevice");
  d->presentation_ = wantSwapchain;
  vkGetDeviceQueue(d->device_, d->queueFamily_, 0, &d->queue_);

  VkCommandPoolCreateInfo pci = vkStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
  pci.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  pci.queueFamilyIndex = d->queueFamily_;
  check(vkCreateCommandPool(d->device_, &pci, nullptr, &d->uploadPool_), "vkCreateCommandPool");

  spdlog::info("tsr::vk: using {} (Vulkan {}.{}.{}){}", d->properties_.deviceName,
               VK_API_VERSION_MAJOR(d->properties_.apiVersion), VK_API_VERSION_MINOR(d->properties_.apiVersion),
               VK_API_VERSION_PATCH(d->properties_.apiVersion), options.validation ? ", validation on" : "");
  return d;
}

Device::~Device() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    if (uploadPool_) vkDestroyCommandPool(device_, uploadPool_, nullptr);
    vkDestroyDevice(device_, nullptr);
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
}

std::uint32_t Device::memoryType(std::uint32_t typeBits, VkMemoryPropertyFlags required) const {
  for (std::uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
    if ((typeBits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & required) == required) return i;
  throw Error("no memory type with the required properties");
}

void Device::submitAndWait(const std::function<void(VkCommandBuffer)>& record) const {
  VkCommandBufferAllocateInfo ai =
      vkStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
  ai.commandPool = uploadPool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  check(vkAllocateCommandBuffers(device_, &ai, &cmd), "vkAllocateCommandBuffers");
  struct Free {
    VkDevice device;
    VkCommandPool pool;
    VkCommandBuffer cmd;
    ~Free() { vkFreeCommandBuffers(device, pool, 1, &cmd); }
  } guard{device_, uploadPool_, cmd};
  VkCommandBufferBeginInfo bi = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
  record(cmd);
  check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
  VkSubmitInfo si = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  check(vkQueueSubmit(queue_, 1, &si, VK_NULL_HANDLE), "vkQueueSubmit");
  check(vkQueueWaitIdle(queue_), "vkQueueWaitIdle");
}

}  // namespace tsr::vk
