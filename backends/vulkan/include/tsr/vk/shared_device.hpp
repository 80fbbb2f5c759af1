#pragma once
// One Vulkan device per process: lavapipe (and most drivers) gain nothing
// from several, and each costs an instance, a queue and pipelines. Every
// user in the process (the rasterizer's contexts, the coverage id pass)
// takes it from here, so a layered coverage + Vulkan render opens one.
#include <memory>
#include <mutex>

#include "tsr/vk/device.hpp"

namespace tsr::vk {

struct SharedDevice {
  std::shared_ptr<Device> device;
  // Device is not thread-safe (one queue, one upload pool): every scene
  // edit and render through it holds this lock, whoever it is for.
  std::mutex mutex;
};

// The process's device, created on first use and freed with its last user.
std::shared_ptr<SharedDevice> sharedDevice();

}  // namespace tsr::vk
