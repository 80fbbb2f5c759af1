#include "post/depth_of_field.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace tsr::vk {

float blurPixelsPerUnit(const Camera& camera, const Region& region) {
  // The window spans right - left on the plane z = -near; at the focus
  // plane a unit is near / focusDistance of that window.
  return float(region.width) * camera.near / ((camera.right - camera.left) * camera.focusDistance);
}

float blurRadius(const Camera& camera, float pixelsPerUnit, float z) {
  const float spread = std::isfinite(z) ? std::abs(z - camera.focusDistance) / z : 1.0f;
  return std::min(kMaxBlurPixels, camera.apertureRadius * spread * pixelsPerUnit);
}

namespace {

constexpr int kSamples = 128;  // over the disk a pixel gathers from, besides itself
constexpr float kGoldenAngle = 2.39996323f;
constexpr float kPi = 3.14159265f;

// Where the samples lie in the unit disk: a golden-angle spiral, even in
// area, made once.
const std::array<glm::vec2, kSamples>& spiral() {
  static const std::array<glm::vec2, kSamples> points = [] {
    std::array<glm::vec2, kSamples> p;
    for (int k = 0; k < kSamples; ++k) {
      const float r = std::sqrt((float(k) + 0.5f) / float(kSamples)), a = float(k) * kGoldenAngle;
      p[std::size_t(k)] = {r * std::cos(a), r * std::sin(a)};
    }
    return p;
  }();
  return points;
}

}  // namespace

void applyDepthOfField(const Camera& camera, const Region& drawn, std::span<glm::vec4> colour,
                       std::span<const float> depth) {
  const float pixelsPerUnit = blurPixelsPerUnit(camera, drawn);
  const std::uint32_t width = drawn.regionWidth(), height = drawn.regionHeight();
  const std::size_t pixels = std::size_t(width) * height;
  std::vector<float> radius(pixels);
  float largest = 0.0f;
  for (std::size_t i = 0; i < pixels; ++i)
    largest = std::max(largest, radius[i] = blurRadius(camera, pixelsPerUnit, depth[i]));
  if (largest < 0.5f) return;  // nothing blurs by as much as half a pixel

  // How far a pixel gathers from: the largest disk among the tiles that a
  // disk of kMaxBlurPixels could reach it from. Tiles are aligned to the
  // whole image, so a crop decides as the whole image does.
  const std::uint32_t tx0 = drawn.x0 / kBlurTile, ty0 = drawn.y0 / kBlurTile;
  const std::uint32_t tx = (drawn.x1 + kBlurTile - 1) / kBlurTile - tx0,
                      ty = (drawn.y1 + kBlurTile - 1) / kBlurTile - ty0;
  std::vector<float> tileMax(std::size_t(tx) * ty, 0.0f);
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x) {
      float& m = tileMax[std::size_t((y + drawn.y0) / kBlurTile - ty0) * tx + (x + drawn.x0) / kBlurTile - tx0];
      m = std::max(m, radius[std::size_t(y) * width + x]);
    }
  const int reach = int(std::ceil(kMaxBlurPixels / float(kBlurTile)));
  std::vector<float> gather(tileMax.size(), 0.0f);
  for (std::uint32_t j = 0; j < ty; ++j)
    for (std::uint32_t i = 0; i < tx; ++i) {
      float m = 0.0f;
      for (int dj = -reach; dj <= reach; ++dj)
        for (int di = -reach; di <= reach; ++di) {
          const int u = int(i) + di, v = int(j) + dj;
          if (u >= 0 && v >= 0 && u < int(tx) && v < int(ty)) m = std::max(m, tileMax[std::size_t(v) * tx + u]);
        }
      gather[std::size_t(j) * tx + i] = m;
    }

  const std::vector<glm::vec4> sharp(colour.begin(), colour.end());
  const auto& unitDisk = spiral();
  tbb::parallel_for(std::uint32_t(0), height, [&](std::uint32_t y) {
    for (std::uint32_t x = 0; x < width; ++x) {
      const std::size_t p = std::size_t(y) * width + x;
      const float reachOf =
          gather[std::size_t((y + drawn.y0) / kBlurTile - ty0) * tx + (x + drawn.x0) / kBlurTile - tx0];
      if (reachOf < 0.5f) continue;
      const float own = std::max(radius[p], 0.5f);
      // Weights are a sample's share of the image's area over its disk's
      // area: each disk sample an equal part, pi reach^2 / N, of the
      // gathered disk (pi cancels there), the pixel itself one pixel.
      const float share = reachOf * reachOf / float(kSamples);
      const float self = 1.0f / (kPi * own * own);  // one pixel's area, not a disk sample's pi reach^2 / N
      glm::vec4 sum = sharp[p] * self;
      float weights = self;
      for (const glm::vec2& u : unitDisk) {
        // The offset is rounded on its own, so a crop lands on the pixels the whole image does.
        const int qx = std::clamp(int(x) + int(std::floor(reachOf * u.x + 0.5f)), 0, int(width) - 1);
        const int qy = std::clamp(int(y) + int(std::floor(reachOf * u.y + 0.5f)), 0, int(height) - 1);
        const std::size_t q = std::size_t(qy) * width + std::size_t(qx);
        float spread = radius[q];
        if (depth[q] > depth[p]) spread = std::min(spread, radius[p]);  // behind: no farther than this one's disk
        spread = std::max(spread, 0.5f);
        const float dx = float(qx) - float(x), dy = float(qy) - float(y);
        if (dx * dx + dy * dy > spread * spread) continue;  // its disk does not reach this pixel
        const float w = share / (spread * spread);
        sum += sharp[q] * w;
        weights += w;
      }
      colour[p] = sum / weights;
    }
  });
}

}  // namespace tsr::vk
