#include "tsr/backend/embree_device.hpp"

#include <spdlog/spdlog.h>

namespace tsr::backend {

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

EmbreeDevice::EmbreeDevice(Raise raise, const std::string& config) : raise_(raise) {
  device_ = rtcNewDevice(config.empty() ? nullptr : config.c_str());
  if (!device_) raise_("rtcNewDevice failed: " + std::string(errorName(rtcGetDeviceError(nullptr))));
  rtcSetDeviceErrorFunction(device_, &EmbreeDevice::onError, this);
}

EmbreeDevice::~EmbreeDevice() { rtcReleaseDevice(device_); }

void EmbreeDevice::onError(void* self, RTCError code, const char* message) {
  auto* device = static_cast<EmbreeDevice*>(self);
  std::string text = std::string(errorName(code)) + ": " + (message ? message : "");
  spdlog::error("embree: {}", text);
  std::lock_guard lock(device->mutex_);
  if (device->pending_.empty()) device->pending_ = text;
}

void EmbreeDevice::check(const char* during) const {
  std::string text;
  {
    std::lock_guard lock(mutex_);
    text.swap(pending_);
  }
  if (!text.empty()) raise_(std::string("Embree error during ") + during + ": " + text);
}

}  // namespace tsr::backend
