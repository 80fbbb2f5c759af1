#include "shared_device.hpp"

namespace tsr::med::vulkan_mediator {

std::shared_ptr<SharedDevice> sharedDevice() {
  static std::mutex mutex;
  static std::weak_ptr<SharedDevice> held;
  std::lock_guard lock(mutex);
  if (auto shared = held.lock()) return shared;
  auto shared = std::make_shared<SharedDevice>();
  shared->device = vk::Device::create();
  held = shared;
  return shared;
}

}  // namespace tsr::med::vulkan_mediator
