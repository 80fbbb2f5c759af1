#pragma once

#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>

namespace tsr::vk {

// Every invalid argument and every Vulkan failure surfaces as this type, so a
// mediator can catch one thing and report the message.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error("tsr::vk: " + message) {}
};

// "VK_ERROR_OUT_OF_DEVICE_MEMORY" etc.; "VkResult(<n>)" for unknown codes.
const char* resultName(VkResult result);

// Throws Error("<what> failed: <VkResult name>") unless result is VK_SUCCESS.
void check(VkResult result, const char* what);

}  // namespace tsr::vk
