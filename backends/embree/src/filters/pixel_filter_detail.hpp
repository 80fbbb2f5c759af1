#pragma once

// Internals shared by pixel_filter.cpp (API, blend, adaptive widths) and
// pixel_filter_kernels.cpp (the three filters). Images are planes of floats
// (structure of arrays) so the inner loops over a row vectorise.

#include <bit>
#include <cstdint>
#include <functional>
#include <vector>

namespace tsr::embree::pf {

using Plane = std::vector<float>;

// Range buffer, pre-scaled so that the range exponent is a plain squared
// distance: c / (sqrt(2) sigmaC), d / (sqrt(2) sigmaD) and the flash's
// spread e / (sqrt(2) sigmaC). Background (non-finite depth) is
// kBackground, so background and hit pixels never weigh each other while
// background pixels gather one another. The spread keeps pixels that mix
// two surfaces (silhouettes, texture edges) apart from pixels of either:
// their mean colour can match a third pixel whose radiance is not theirs,
// which darkened or brightened silhouettes.
struct Range {
  Plane r, g, b, d, e;
};
inline constexpr float kBackground = 1e15f;      // squared: 1e30, finite; exp(-1e30) = 0
inline constexpr float kMaxScaledDepth = 1e12f;  // clamp of scaled finite colours and depths

// The data that is filtered, plus the first and second moments of each
// pixel's composite kernel per image axis (offsets relative to the pixel).
// The moments give r for the multi-pass kernels (see momentReduction).
struct State {
  Plane lr, lg, lb;  // radiance
  Plane v;           // scalar variance
  Plane mx, vx;      // composite kernel: mean x offset and variance along x
  Plane my, vy;      // the same along y
  Plane q;           // sum (a_i/A)^2 q_i pass by pass: r if the pass inputs were independent
};

struct Image {
  int w = 0, h = 0;
};

// exp(x) for x <= 0: 2^n times a degree-7 polynomial for the fraction;
// relative error < 2e-6, exactly 1 at 0, exactly 0 below -87. Branch-free
// so the loops that call it vectorise; the same inputs give the same bits
// on any thread.
inline float fastExp(float x) {
  const float xc = x < -87.0f ? -87.0f : x;
  const float y = xc * 1.44269504f;
  const int n = static_cast<int>(y);                           // towards zero: n <= 0
  const float t = (y - static_cast<float>(n)) * 0.693147181f;  // (-ln2, 0]
  const float p =
      1.0f + t * (1.0f + t * (0.5f + t * (1.0f / 6 +
                                          t * (1.0f / 24 + t * (1.0f / 120 + t * (1.0f / 720 + t * (1.0f / 5040)))))));
  const float scale = std::bit_cast<float>(static_cast<std::int32_t>((n + 127) << 23));
  return x < -87.0f ? 0.0f : p * scale;
}

// Both r estimates of the multi-pass kernels are (nearly) lower bounds of
// the true sum a_i^2: the moment model because a Gaussian has almost the
// smallest sum a^2 for its variance (an Epanechnikov kernel is 5% lower),
// the propagated q because later passes average positively correlated
// pixels. So r = max(q, momentReduction): q wins where a kernel gathers a
// few scattered pixels (a wide footprint with little averaging), the
// moments where passes re-average the same neighbourhood.
//
// r = sum a_i^2 of a normalised 2-D kernel whose marginals have variances
// sx2 and sy2 (pixels^2), assuming a Gaussian-like shape: a 1-D discrete
// kernel of variance s2 has sum a^2 ~ 1/sqrt(1 + 4 pi s2) (exact for a
// single tap, asymptotically exact for wide Gaussians, within 2.5% for boxes).
float momentReduction(float sx2, float sy2);

// Runs body(y0, y1) over row ranges in a TBB arena of `threads` workers
// (0 = all). Every row is computed by the same code whichever the split, so
// the result does not depend on the thread count.
void parallelRows(int threads, int rows, const std::function<void(int, int)>& body);

struct KernelParams {
  int threads = 0;
  unsigned iterations = 3;
  bool antialiasRecovery = false;
};

// Each writes the filtered state (radiance, variance, moments) and r.
// sigma: per-pixel spatial sigma (combined over passes).
void bilateral(const Image& im, const Range& range, const Plane& sigma, State& s, Plane& r, const KernelParams& p);
void separable(const Image& im, const Range& range, const Plane& sigma, State& s, Plane& r, const KernelParams& p);
void atrous(const Image& im, const Range& range, const Plane& sigma, State& s, Plane& r, const KernelParams& p);

}  // namespace tsr::embree::pf
