#pragma once
// The rectangles of a display wall within its virtual frame. Bezels hide
// pixels: the image continues behind them, so a tile's rectangle is where
// its screen sits in the virtual frame and the gap pixels belong to no tile.
#include <optional>
#include <vector>

#include "tsr/cluster/cluster_config.hpp"
#include "tsr/med/view.hpp"

namespace tsr::cluster {

// Tiles row by row from the top left. Throws std::invalid_argument when the
// bezels leave no pixels for a tile.
std::vector<med::PixelRect> wallLayout(std::uint32_t width, std::uint32_t height, std::uint32_t columns,
                                       std::uint32_t rows, std::uint32_t bezel);

// What one wall screen renders: its pixels in the rendered frame and the eye.
struct ScreenRect {
  med::PixelRect rect;
  std::optional<med::Eye> eye;
};

// The screens of `wall` in a rendered frame of width x height, in config
// order: the grid, or each screen's rectangle (bezel applied, clipped to
// the frame) scaled from the wall's virtual frame. Throws
// std::invalid_argument when a screen is left without pixels.
std::vector<ScreenRect> wallScreens(const WallConfig& wall, std::uint32_t width, std::uint32_t height);

// A grid of square-ish tiles of at most `tileSize` pixels covering the image.
std::vector<med::PixelRect> tileGrid(std::uint32_t width, std::uint32_t height, std::uint32_t tileSize);

}  // namespace tsr::cluster
