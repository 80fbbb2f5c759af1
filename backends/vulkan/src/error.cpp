#include "tsr/vk/error.hpp"

#include <string>

namespace tsr::vk {

const char* resultName(VkResult result) {
  switch (result) {
#define TSR_VK_CASE(r) \
  case r:              \
    return #r;
    TSR_VK_CASE(VK_SUCCESS)
    TSR_VK_CASE(VK_NOT_READY)
    TSR_VK_CASE(VK_TIMEOUT)
    TSR_VK_CASE(VK_EVENT_SET)
    TSR_VK_CASE(VK_EVENT_RESET)
    TSR_VK_CASE(VK_INCOMPLETE)
    TSR_VK_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    TSR_VK_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    TSR_VK_CASE(VK_ERROR_INITIALIZATION_FAILED)
    TSR_VK_CASE(VK_ERROR_DEVICE_LOST)
    TSR_VK_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    TSR_VK_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    TSR_VK_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    TSR_VK_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    TSR_VK_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    TSR_VK_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    TSR_VK_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    TSR_VK_CASE(VK_ERROR_FRAGMENTED_POOL)
    TSR_VK_CASE(VK_ERROR_UNKNOWN)
    TSR_VK_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    TSR_VK_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE)
    TSR_VK_CASE(VK_ERROR_FRAGMENTATION)
    TSR_VK_CASE(VK_ERROR_SURFACE_LOST_KHR)
    TSR_VK_CASE(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
    TSR_VK_CASE(VK_SUBOPTIMAL_KHR)
    TSR_VK_CASE(VK_ERROR_OUT_OF_DATE_KHR)
    TSR_VK_CASE(VK_ERROR_VALIDATION_FAILED_EXT)
#undef TSR_VK_CASE
    default:
      break;
  }
  thread_local std::string unknown;
  unknown = "VkResult(" + std::to_string(static_cast<int>(result)) + ")";
  return unknown.c_str();
}

void check(VkResult result, const char* what) {
  if (result != VK_SUCCESS) throw Error(std::string(what) + " failed: " + resultName(result));
}

}  // namespace tsr::vk
