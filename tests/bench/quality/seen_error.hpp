#pragma once
// The seen error of the trusted-previews issue: what a person sees differ.
// Both images are mapped to what a PNG shows (clamp to [0, 1], sRGB
// encode), blurred with a box of radius 2 applied twice (this removes the
// reference's own residual grain, and the grain a viewer's eye does not
// resolve either), and compared by RMSE over the whole image and over the
// worst 16x16 tile. relMSE is blind to what it calls good here: a wrong
// reflection or remaining speckle costs little relMSE next to a firefly.
// Shared by the quality harness and the property tests.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

namespace tsr::quality {

inline constexpr int kSeenBlurRadius = 2;
inline constexpr int kSeenTile = 16;

struct SeenError {
  double whole = 0;                      // RMSE over every pixel and RGB channel
  double worstTile = 0;                  // the largest RMSE of one 16x16 tile (border tiles may be smaller)
  std::uint32_t worstX = 0, worstY = 0;  // that tile's top-left pixel
};

// Linear value -> displayed sRGB value in [0, 1].
inline float displayed(float linear) {
  const float c = std::clamp(std::isfinite(linear) ? linear : 0.0f, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

// A box mean of radius r along one axis, windows cut at the border
// (the mean over the pixels inside).
inline void boxPass(const std::vector<float>& in, std::vector<float>& out, int w, int h, int r, bool alongX) {
  out.assign(in.size(), 0.0f);
  const int len = alongX ? w : h, lines = alongX ? h : w;
  for (int line = 0; line < lines; ++line)
    for (int i = 0; i < len; ++i) {
      double s = 0;
      const int lo = std::max(0, i - r), hi = std::min(len - 1, i + r);
      for (int k = lo; k <= hi; ++k) s += in[alongX ? std::size_t(line) * w + k : std::size_t(k) * w + line];
      out[alongX ? std::size_t(line) * w + i : std::size_t(i) * w + line] = float(s / double(hi - lo + 1));
    }
}

// Displayed and de-grained channel planes (3 x w x h).
inline std::vector<std::vector<float>> seenPlanes(const std::vector<glm::vec4>& image, int w, int h) {
  std::vector<std::vector<float>> planes(3, std::vector<float>(image.size()));
  std::vector<float> tmp;
  for (int c = 0; c < 3; ++c) {
    for (std::size_t i = 0; i < image.size(); ++i) planes[c][i] = displayed(image[i][c]);
    for (int pass = 0; pass < 2; ++pass) {
      boxPass(planes[c], tmp, w, h, kSeenBlurRadius, true);
      boxPass(tmp, planes[c], w, h, kSeenBlurRadius, false);
    }
  }
  return planes;
}

// Throws std::invalid_argument when the images are empty or their sizes
// do not match width x height.
inline SeenError seenError(const std::vector<glm::vec4>& image, const std::vector<glm::vec4>& reference,
                           std::uint32_t width, std::uint32_t height) {
  const std::size_t n = std::size_t(width) * height;
  if (n == 0 || image.size() != n || reference.size() != n)
    throw std::invalid_argument("seenError: images of " + std::to_string(image.size()) + " and " +
                                std::to_string(reference.size()) + " pixels for " + std::to_string(width) + "x" +
                                std::to_string(height));
  const int w = int(width), h = int(height);
  const auto a = seenPlanes(image, w, h), b = seenPlanes(reference, w, h);
  SeenError e;
  double total = 0;
  for (int ty = 0; ty < h; ty += kSeenTile)
    for (int tx = 0; tx < w; tx += kSeenTile) {
      double sum = 0;
      std::size_t count = 0;
      for (int y = ty; y < std::min(h, ty + kSeenTile); ++y)
        for (int x = tx; x < std::min(w, tx + kSeenTile); ++x)
          for (int c = 0; c < 3; ++c) {
            const std::size_t i = std::size_t(y) * w + x;
            const double d = double(a[c][i]) - b[c][i];
            sum += d * d;
            ++count;
          }
      total += sum;
      const double tile = std::sqrt(sum / double(count));
      if (tile > e.worstTile) {
        e.worstTile = tile;
        e.worstX = std::uint32_t(tx);
        e.worstY = std::uint32_t(ty);
      }
    }
  e.whole = std::sqrt(total / (3.0 * double(n)));
  return e;
}

}  // namespace tsr::quality
