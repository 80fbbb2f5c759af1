#include "tsr/backend/region.hpp"

namespace tsr::backend {

std::optional<std::string> Region::invalidReason() const {
  if (width == 0 || height == 0) return "image size must be non-zero";
  if (!(x0 < x1 && y0 < y1)) return "region is empty (need x0 < x1 and y0 < y1)";
  if (x1 > width || y1 > height) {
    return "region [" + std::to_string(x0) + "," + std::to_string(x1) + ")x[" + std::to_string(y0) + "," +
           std::to_string(y1) + ") exceeds image " + std::to_string(width) + "x" + std::to_string(height);
  }
  return std::nullopt;
}

}  // namespace tsr::backend
