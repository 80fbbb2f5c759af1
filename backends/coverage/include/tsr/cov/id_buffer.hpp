#pragma once

#include "tsr/cov/ids.hpp"
#include "tsr/cov/vocabulary.hpp"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace tsr::cov {

inline constexpr float kNoDepth = std::numeric_limits<float>::infinity();

// What an id pass produced for one region: per pixel (row-major, row 0 at
// the top of the region) the ObjectId seen through the pixel centre
// (kBackground where nothing opaque was hit) and its camera-space depth
// (distance along -Z in camera space; kNoDepth on the background).
struct IdBuffer {
  Region region;
  std::vector<ObjectId> ids;
  std::vector<float> depth;

  IdBuffer() = default;
  explicit IdBuffer(const Region& r);

  std::uint32_t width() const { return region.regionWidth(); }
  std::uint32_t height() const { return region.regionHeight(); }
  std::size_t index(std::uint32_t x, std::uint32_t y) const { return std::size_t{y} * width() + x; }
  ObjectId id(std::uint32_t x, std::uint32_t y) const { return ids[index(x, y)]; }
};

}  // namespace tsr::cov
