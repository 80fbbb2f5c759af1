#include "tsr/embree/visible_difference.hpp"

#include "tsr/embree/error.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace tsr::embree {

namespace {

using Image = std::vector<float>;

// Separable Gaussian, edges clamped. sigma 0 copies.
Image blur(const Image& in, std::uint32_t w, std::uint32_t h, float sigma) {
  if (!(sigma > 0.0f)) return in;
  const int r = std::max(1, int(std::ceil(3.0f * sigma)));
  std::vector<float> k(2 * r + 1);
  float sum = 0.0f;
  for (int i = -r; i <= r; ++i) sum += k[i + r] = std::exp(-float(i * i) / (2.0f * sigma * sigma));
  for (float& v : k) v /= sum;
  Image tmp(in.size()), out(in.size());
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x) {
      float acc = 0.0f;
      for (int i = -r; i <= r; ++i) acc += k[i + r] * in[y * w + std::clamp<int>(int(x) + i, 0, int(w) - 1)];
      tmp[y * w + x] = acc;
    }
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x) {
      float acc = 0.0f;
      for (int i = -r; i <= r; ++i) acc += k[i + r] * tmp[std::clamp<int>(int(y) + i, 0, int(h) - 1) * w + x];
      out[y * w + x] = acc;
    }
  return out;
}

// Mannos & Sakrison (1974), peak 1 near 8 cycles per degree.
float csf(float f) { return 2.6f * (0.0192f + 0.114f * f) * std::exp(-std::pow(0.114f * f, 1.1f)) / 0.981f; }

}  // namespace

void VisibleDifferenceSettings::validate() const {
  if (!(pixelsPerDegree > 0.0f) || !(peakSensitivity > 0.0f) || !(maskingSlope >= 0.0f) || !(adaptationFloor > 0.0f) ||
      !std::isfinite(pixelsPerDegree + peakSensitivity + maskingSlope + adaptationFloor))
    throw Error("visible difference settings must be finite and positive");
}

VisibleDifference predictVisibleDifference(std::span<const float> a, std::span<const float> b, std::uint32_t w,
                                           std::uint32_t h, const VisibleDifferenceSettings& s) {
  s.validate();
  const std::size_t n = std::size_t(w) * h;
  if (n == 0 || a.size() != n || b.size() != n)
    throw Error("visible difference: images must both be " + std::to_string(w) + "x" + std::to_string(h));
  Image la(a.begin(), a.end()), lb(b.begin(), b.end());
  for (float& v : la) v = std::isfinite(v) ? std::max(v, 0.0f) : 0.0f;
  for (float& v : lb) v = std::isfinite(v) ? std::max(v, 0.0f) : 0.0f;
  Image mean(n);
  for (std::size_t i = 0; i < n; ++i) mean[i] = 0.5f * (la[i] + lb[i]);
  const Image adaptation = blur(mean, w, h, 0.5f * s.pixelsPerDegree);

  VisibleDifference out;
  out.jnd.assign(n, 0.0f);
  std::vector<float> pooled(n, 0.0f);
  Image prevA = la, prevB = lb;
  for (int k = 0; std::ldexp(1.0f, k) <= 0.25f * float(std::min(w, h)); ++k) {
    const float sigma = std::ldexp(1.0f, k);
    Image nextA = blur(la, w, h, sigma), nextB = blur(lb, w, h, sigma);
    const float f = s.pixelsPerDegree / std::ldexp(4.0f, k);
    const float sens = s.peakSensitivity * csf(f);
    for (std::size_t i = 0; i < n; ++i) {
      const float adapt = std::max(adaptation[i], s.adaptationFloor);
      const float ca = (prevA[i] - nextA[i]) / adapt, cb = (prevB[i] - nextB[i]) / adapt;
      const float mask = std::max(1.0f, std::pow(sens * std::min(std::abs(ca), std::abs(cb)), s.maskingSlope));
      const float r = sens * std::abs(ca - cb) / mask;
      pooled[i] += r * r * r * r;
    }
    prevA = std::move(nextA);
    prevB = std::move(nextB);
  }
  double sum = 0.0;
  std::size_t visible = 0;
  for (std::size_t i = 0; i < n; ++i) {
    out.jnd[i] = std::pow(pooled[i], 0.25f);
    sum += out.jnd[i];
    visible += out.jnd[i] > 1.0f;
  }
  out.meanJnd = float(sum / double(n));
  out.fractionVisible = float(double(visible) / double(n));
  return out;
}

}  // namespace tsr::embree
