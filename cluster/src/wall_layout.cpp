#include "tsr/cluster/wall_layout.hpp"

#include <algorithm>
#include <stdexcept>

namespace tsr::cluster {

namespace {
// Splits `total` pixels minus the gaps into `parts` spans as even as possible.
std::vector<std::pair<std::uint32_t, std::uint32_t>> spans(std::uint32_t total, std::uint32_t parts, std::uint32_t gap) {
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

std::vector<med::PixelRect> tileGrid(std::uint32_t width, std::uint32_t height, std::uint32_t tileSize) {
  if (tileSize == 0) throw std::invalid_argument("tile size 0");
  std::vector<med::PixelRect> out;
  for (std::uint32_t y = 0; y < height; y += tileSize)
    for (std::uint32_t x = 0; x < width; x += tileSize)
      out.push_back({x, y, std::min(width, x + tileSize), std::min(height, y + tileSize)});
  return out;
}

}  // namespace tsr::cluster
