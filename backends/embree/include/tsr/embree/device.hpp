#pragma once

#include "tsr/backend/embree_device.hpp"
#include "tsr/embree/error.hpp"

#include <string>

namespace tsr::embree {

// The shared Embree device (backends/common/embree_device), reporting
// Embree's failures as this back-end's Error.
class Device : public backend::EmbreeDevice {
 public:
  explicit Device(const std::string& config = "")
      : EmbreeDevice([](const std::string& message) { throw Error(message); }, config) {}
};

}  // namespace tsr::embree
