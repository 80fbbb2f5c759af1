#pragma once

#include <embree3/rtcore.h>

#include <mutex>
#include <string>

namespace tsr::embree {

// Owns the RTCDevice. Embree reports errors through a C callback that must
// not throw; the callback logs and records the error, and check() turns the
// recorded error into an Error exception at a point where unwinding is safe.
class Device {
 public:
  explicit Device(const std::string& config = "");
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  RTCDevice handle() const { return device_; }

  // Throws Error if Embree reported an error since the last check.
  void check(const char* during) const;

 private:
  static void onError(void* self, RTCError code, const char* message);

  RTCDevice device_ = nullptr;
  mutable std::mutex mutex_;
  mutable std::string pending_;
};

}  // namespace tsr::embree
