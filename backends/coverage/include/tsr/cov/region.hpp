#pragma once

#include <cstdint>

namespace tsr::cov {

// A pixel rectangle [x0, x1) x [y0, y1) of a full image of width x height
// (row 0 at the top). Rays go through pixel centres of the full image, so a
// region holds exactly the ids of the same crop of the full image.
struct Region {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t x0 = 0;
  std::uint32_t y0 = 0;
  std::uint32_t x1 = 0;
  std::uint32_t y1 = 0;

  static Region full(std::uint32_t width, std::uint32_t height) { return {width, height, 0, 0, width, height}; }
  std::uint32_t regionWidth() const { return x1 - x0; }
  std::uint32_t regionHeight() const { return y1 - y0; }
  std::uint64_t pixelCount() const { return std::uint64_t{regionWidth()} * regionHeight(); }

  // Throws Error on an empty image or a rectangle outside it.
  void validate() const;

  bool operator==(const Region&) const = default;
};

}  // namespace tsr::cov
