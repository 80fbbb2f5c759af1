#include "tsr/temporal/frame.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace tsr::temporal {

void checkSequence(const std::vector<Frame>& frames) {
  if (frames.empty()) throw std::invalid_argument("temporal: no frames");
  const Frame& first = frames.front();
  if (first.pixels() == 0) throw std::invalid_argument("temporal: empty frame");
  for (std::size_t t = 0; t < frames.size(); ++t) {
    const Frame& f = frames[t];
    if (f.width != first.width || f.height != first.height || f.rgb.size() != f.pixels() * 3)
      throw std::invalid_argument("temporal: frame " + std::to_string(t) + " is " + std::to_string(f.width) + "x" +
                                  std::to_string(f.height) + " with " + std::to_string(f.rgb.size()) +
                                  " values; frame 0 is " + std::to_string(first.width) + "x" +
                                  std::to_string(first.height));
    for (float v : f.rgb)
      if (!std::isfinite(v))
        throw std::invalid_argument("temporal: frame " + std::to_string(t) + " holds a non-finite value");
  }
}

}  // namespace tsr::temporal
