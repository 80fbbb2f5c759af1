#include "resources/device_memory.hpp"

#include <string>

#include "tsr/vk/error.hpp"
#include "vk_struct.hpp"

namespace tsr::vk {

namespace {

template <class Bind>
VkDeviceMemory allocateAndBind(const Device& device, const VkMemoryRequirements& req, VkMemoryPropertyFlags properties,
                               const char* what, const char* bindName, Bind bind) {
  VkMemoryAllocateInfo mai = vkStruct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
  mai.allocationSize = req.size;
  mai.memoryTypeIndex = device.memoryType(req.memoryTypeBits, properties);
  VkDeviceMemory memory = VK_NULL_HANDLE;
  // The messages are only built when a call fails.
  const VkResult allocated = vkAllocateMemory(device.handle(), &mai, nullptr, &memory);
  if (allocated != VK_SUCCESS) check(allocated, ("vkAllocateMemory (" + std::string(what) + ")").c_str());
  const VkResult bound = bind(memory);
  if (bound != VK_SUCCESS) {
    vkFreeMemory(device.handle(), memory, nullptr);
    check(bound, (std::string(bindName) + " (" + what + ")").c_str());
  }
  return memory;
}

}  // namespace

VkDeviceMemory bindNewMemory(const Device& device, VkImage image, VkMemoryPropertyFlags properties, const char* what) {
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device.handle(), image, &req);
  return allocateAndBind(device, req, properties, what, "vkBindImageMemory",
                         [&](VkDeviceMemory m) { return vkBindImageMemory(device.handle(), image, m, 0); });
}

VkDeviceMemory bindNewMemory(const Device& device, VkBuffer buffer, VkMemoryPropertyFlags properties,
                             const char* what) {
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device.handle(), buffer, &req);
  return allocateAndBind(device, req, properties, what, "vkBindBufferMemory",
                         [&](VkDeviceMemory m) { return vkBindBufferMemory(device.handle(), buffer, m, 0); });
}

}  // namespace tsr::vk
