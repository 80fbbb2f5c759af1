#pragma once

#include "tsr/cov/id_buffer.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace tsr::cov {

// One visible object: how many pixels of the region show it, and that as a
// fraction of all the region's pixels (background included, so the
// fractions of all objects plus the background's sum to 1).
struct Coverage {
  ObjectId id = kBackground;
  std::uint64_t pixels = 0;
  double fraction = 0.0;
  bool operator==(const Coverage&) const = default;
};

// Objects seen in `ids`, by pixels descending, ties by id ascending; the
// background is left out. Counts in parallel with per-thread histograms,
// O(pixels + visible objects), whichever renderer produced the buffer.
std::vector<Coverage> rank(const IdBuffer& buffer);
std::vector<Coverage> rank(std::span<const ObjectId> ids);

// Pixels of `ids` that show the background.
std::uint64_t backgroundPixels(std::span<const ObjectId> ids);

}  // namespace tsr::cov
