#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace tsr::backend {

// A pixel rectangle [x0, x1) x [y0, y1) of a full image of width x height
// (row 0 at the top). Every back-end renders a region as exactly the same
// crop of the full image: the path tracer keys its random numbers by
// full-image pixels, the rasterizer projects the off-axis sub-window, the
// id pass shoots rays through full-image pixel centres.
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

  // Why no back-end can render it (an empty image, a rectangle that is
  // empty or outside the image), or nothing; see validate.hpp.
  std::optional<std::string> invalidReason() const;

  bool operator==(const Region&) const = default;
};

}  // namespace tsr::backend
