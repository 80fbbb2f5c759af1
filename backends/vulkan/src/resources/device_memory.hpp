#pragma once
// Device memory for one image or buffer: allocated to its requirements with
// the given properties and bound to it, or freed again if binding fails.
#include <vulkan/vulkan.h>

#include "tsr/vk/device.hpp"

namespace tsr::vk {

// `what` names the resource in the error a failure throws.
VkDeviceMemory bindNewMemory(const Device& device, VkImage image, VkMemoryPropertyFlags properties, const char* what);
VkDeviceMemory bindNewMemory(const Device& device, VkBuffer buffer, VkMemoryPropertyFlags properties, const char* what);

}  // namespace tsr::vk
