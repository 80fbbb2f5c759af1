#include "embree_device.hpp"

#include "tsr/cov/error.hpp"

#include <spdlog/spdlog.h>

namespace tsr::cov {

EmbreeDevice::EmbreeDevice() {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw Error("rtcNewDevice failed (error " + std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
  rtcSetDeviceErrorFunction(device_, &EmbreeDevice::onError, this);
}

EmbreeDevice::~EmbreeDevice() { rtcReleaseDevice(device_); }

void EmbreeDevice::onError(void* self, RTCError code, const char* message) {
  auto* device = static_cast<EmbreeDevice*>(self);
  std::string text = "code " + std::to_string(int(code)) + ": " + (message ? message : "");
  spdlog::error("tsr::cov: embree {}", text);
  std::lock_guard lock(device->mutex_);
  if (device->pending_.empty()) device->pending_ = text;
}

void EmbreeDevice::check(const char* during) const {
  std::string text;
  {
    std::lock_guard lock(mutex_);
    text.swap(pending_);
  }
  if (!text.empty()) throw Error(std::string("Embree error during ") + during + ": " + text);
}

}  // namespace tsr::cov
