#pragma once

#include <stdexcept>
#include <string>

namespace tsr::cov {

// Every invalid argument and every failure of the ray tracer surfaces as
// this type, so a caller can catch one thing and report the message.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error("tsr::cov: " + message) {}
};

}  // namespace tsr::cov
