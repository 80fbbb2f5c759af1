#pragma once
// One Vulkan device per process: lavapipe (and most drivers) gain nothing
// from several, and each costs an instance, a queue and pipelines.
#include <memory>
#include <mutex>

#include "tsr/vk/device.hpp"

namespace tsr::med::vulkan_mediator {

struct SharedDevice {
  std::shared_ptr<vk::Device> device;
  // vk::Device is not thread-safe (one queue, one upload pool): every scene
  // edit and render through it holds this lock, whichever context it is for.
  std::mutex mutex;
};

// The process's device, created on first use and freed with its last user.
std::shared_ptr<SharedDevice> sharedDevice();

}  // namespace tsr::med::vulkan_mediator
