#include "tsr/cluster/wall_layout.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace tsr::cluster {

namespace {
// Splits `total` pixels minus the gaps into `parts` spans as even as possible.
std::vector<std::pair<std::uint32_t, std::uint32_t>> spans(std::uint32_t total, std::uint32_t parts,
                                                           std::uint32_t gap) {
  std::uint64_t gaps = std::uint64_t{gap} * (parts - 1);
  if (parts == 0 || gaps >= total || total - gaps < parts)
    throw std::invalid_argument("wall layout: bezels leave no pixels for the tiles");
  std::uint32_t usable = total - static_cast<std::uint32_t>(gaps);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  std::uint32_t at = 0;
  for (std::uint32_t i = 0; i < parts; ++i) {
    std::uint32_t size = usable / parts + (i < usable % parts ? 1 : 0);
    out.emplace_back(at, at + size);
    at += size + gap;
  }
  return out;
}
}  // namespace

std::vector<med::PixelRect> wallLayout(std::uint32_t width, std::uint32_t height, std::uint32_t columns,
                                       std::uint32_t rows, std::uint32_t bezel) {
  auto xs = spans(width, columns, bezel);
  auto ys = spans(height, rows, bezel);
  std::vector<med::PixelRect> out;
  for (const auto& [y0, y1] : ys)
    for (const auto& [x0, x1] : xs) out.push_back({x0, y0, x1, y1});
  return out;
}

std::vector<ScreenRect> wallScreens(const WallConfig& wall, std::uint32_t width, std::uint32_t height) {
  std::vector<ScreenRect> out;
  if (wall.screens.empty()) {
    for (const auto& r : wallLayout(width, height, wall.columns, wall.rows, wall.bezel))
      out.push_back({r, std::nullopt});
    return out;
  }
  if (wall.frameWidth == 0 || wall.frameHeight == 0)
    throw std::invalid_argument("wall layout: the virtual frame has no size");
  // In the frame's pixels (64-bit: bezels may be negative), then scaled.
  auto scaled = [](std::int64_t v, std::int64_t limit, std::uint32_t frame, std::uint32_t size) {
    v = std::clamp<std::int64_t>(v, 0, limit);
    return static_cast<std::uint32_t>(v * size / frame);
  };
  for (const auto& s : wall.screens) {
    std::int64_t x0 = std::int64_t{s.x} + s.bezel, y0 = std::int64_t{s.y} + s.bezel;
    std::int64_t x1 = std::int64_t{s.x} + s.width - s.bezel, y1 = std::int64_t{s.y} + s.height - s.bezel;
    med::PixelRect r{
        scaled(x0, wall.frameWidth, wall.frameWidth, width), scaled(y0, wall.frameHeight, wall.frameHeight, height),
        scaled(x1, wall.frameWidth, wall.frameWidth, width), scaled(y1, wall.frameHeight, wall.frameHeight, height)};
    if (r.empty())
      throw std::invalid_argument("wall layout: the screen at " + std::to_string(s.x) + "," + std::to_string(s.y) +
                                  " has no pixels inside the frame at " + std::to_string(width) + "x" +
                                  std::to_string(height));
    out.push_back({r, s.eye});
  }
  return out;
}

std::vector<med::PixelRect> tileGrid(std::uint32_t width, std::uint32_t height, std::uint32_t tileSize) {
  if (tileSize == 0) throw std::invalid_argument("tile size 0");
  std::vector<med::PixelRect> out;
  for (std::uint32_t y = 0; y < height; y += tileSize)
    for (std::uint32_t x = 0; x < width; x += tileSize)
      out.push_back({x, y, std::min(width, x + tileSize), std::min(height, y + tileSize)});
  return out;
}

}  // namespace tsr::cluster
