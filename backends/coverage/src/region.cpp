#include "tsr/cov/region.hpp"

#include "tsr/cov/error.hpp"

#include <string>

namespace tsr::cov {

void Region::validate() const {
  if (width == 0 || height == 0) throw Error("image size must be non-zero");
  if (!(x0 < x1 && y0 < y1)) throw Error("region is empty (need x0 < x1 and y0 < y1)");
  if (x1 > width || y1 > height) {
    throw Error("region [" + std::to_string(x0) + "," + std::to_string(x1) + ")x[" + std::to_string(y0) + "," +
                std::to_string(y1) + ") exceeds image " + std::to_string(width) + "x" + std::to_string(height));
  }
}

}  // namespace tsr::cov
