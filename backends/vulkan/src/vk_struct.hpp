#pragma once

#include <vulkan/vulkan.h>

namespace tsr::vk {

// A zeroed Vulkan info struct with its sType set (brace-initialising only
// sType trips -Wmissing-field-initializers).
template <class T>
T vkStruct(VkStructureType type) {
  T value{};
  value.sType = type;
  return value;
}

}  // namespace tsr::vk
