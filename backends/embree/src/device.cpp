#include "tsr/embree/device.hpp"

#include "tsr/embree/error.hpp"

#include <spdlog/spdlog.h>

namespace tsr::embree {

namespace {
const char* errorName(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE:
      return "none";
    case RTC_ERROR_UNKNOWN:
      return "unknown";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
  }
  return "unrecognised";
}
}  // namespace

Device::Device(const std::string& config) {
  device_ = rtcNewDevice(config.empty() ? nullptr : config.c_str());
  if (!device_) {
    throw Error("rtcNewDevice failed: " + std::string(errorName(rtcGetDeviceError(nullptr))));
  }
  rtcSetDeviceErrorFunction(device_, &Device::onError, this);
}

Device::~Device() { rtcReleaseDevice(device_); }

void Device::onError(void* self, RTCError code, const char* message) {
  auto* device = static_cast<Device*>(self);
  std::string text = std::string(errorName(code)) + ": " + (message ? message : "");
  spdlog::error("embree: {}", text);
  std::lock_guard lock(device->mutex_);
  if (device->pending_.empty()) device->pending_ = text;
}

void Device::check(const char* during) const {
  std::string text;
  {
    std::lock_guard lock(mutex_);
    text.swap(pending_);
  }
  if (!text.empty()) throw Error(std::string("Embree error during ") + during + ": " + text);
}

}  // namespace tsr::embree
