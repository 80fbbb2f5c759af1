#pragma once

#include <embree3/rtcore.h>

#include <mutex>
#include <string>

namespace tsr::cov {

// Owns the RTCDevice. Embree reports errors through a C callback that must
// not throw; the callback records the error and check() turns it into an
// Error where unwinding is safe.
class EmbreeDevice {
 public:
  EmbreeDevice();
  ~EmbreeDevice();
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;

  RTCDevice handle() const { return device_; }
  // Throws Error if Embree reported an error since the last check.
  void check(const char* during) const;

 private:
  static void onError(void* self, RTCError code, const char* message);

  RTCDevice device_ = nullptr;
  mutable std::mutex mutex_;
  mutable std::string pending_;
};

}  // namespace tsr::cov
