#include "filters/image_blur.hpp"

#include "filters/pixel_filter_detail.hpp"

#include <algorithm>
#include <cstddef>

namespace tsr::embree::pf {

std::vector<float> boxMean(const std::vector<float>& in, int w, int h, int radius) {
  std::vector<float> across(in.size()), out(in.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float sum = 0.0f;
      const int x0 = std::max(x - radius, 0), x1 = std::min(x + radius, w - 1);
      for (int i = x0; i <= x1; ++i) sum += in[std::size_t(y) * w + i];
      across[std::size_t(y) * w + x] = sum / float(x1 - x0 + 1);
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float sum = 0.0f;
      const int y0 = std::max(y - radius, 0), y1 = std::min(y + radius, h - 1);
      for (int i = y0; i <= y1; ++i) sum += across[std::size_t(i) * w + x];
      out[std::size_t(y) * w + x] = sum / float(y1 - y0 + 1);
    }
  return out;
}

std::vector<float> blur121(const std::vector<float>& in, int w, int h, int threads) {
  std::vector<float> out(in.size());
  parallelRows(threads, h, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < w; ++x) {
        float sum = 0.0f, weights = 0.0f;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
            const float k = (dx == 0 ? 2.0f : 1.0f) * (dy == 0 ? 2.0f : 1.0f);
            sum += k * in[std::size_t(ny) * w + nx];
            weights += k;
          }
        out[std::size_t(y) * w + x] = sum / weights;
      }
  });
  return out;
}

}  // namespace tsr::embree::pf
