#pragma once

#include <embree3/rtcore.h>

#include <mutex>
#include <string>

namespace tsr::backend {

// Owns the RTCDevice of a back-end that traces with Embree (the path tracer,
// the coverage id pass). Embree reports errors through a C callback that
// must not throw; the callback logs and records the error, and check()
// turns the recorded error into the back-end's exception at a point where
// unwinding is safe.
class EmbreeDevice {
 public:
  // Throws the back-end's Error with `message`; never returns.
  using Raise = void (*)(const std::string& message);

  // config: rtcNewDevice's configuration ("" for Embree's defaults).
  // Raises if Embree makes no device.
  explicit EmbreeDevice(Raise raise, const std::string& config = "");
  ~EmbreeDevice();
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;

  RTCDevice handle() const { return device_; }

  // Raises if Embree reported an error since the last check.
  void check(const char* during) const;

 private:
  static void onError(void* self, RTCError code, const char* message);

  Raise raise_;
  RTCDevice device_ = nullptr;
  mutable std::mutex mutex_;
  mutable std::string pending_;
};

}  // namespace tsr::backend
