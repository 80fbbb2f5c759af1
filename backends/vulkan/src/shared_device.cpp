#include "tsr/vk/shared_device.hpp"

namespace tsr::vk {

std::shared_ptr<SharedDevice> sharedDevice() {
  static std::mutex mutex;
  static std::weak_ptr<SharedDevice> held;
  std::lock_guard lock(mutex);
  if (auto shared = held.lock()) return shared;
  auto shared = std::make_shared<SharedDevice>();
  shared->device = Device::create();
  held = shared;
  return shared;
}

}  // namespace tsr::vk
