#pragma once

#include <stdexcept>
#include <string>

namespace tsr::embree {

// Every invalid argument and every Embree failure surfaces as this type, so a
// mediator can catch one thing and report the message.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error("tsr::embree: " + message) {}
};

}  // namespace tsr::embree
