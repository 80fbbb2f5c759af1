#pragma once
// How many PCA modes to keep (Meyer & Anderson 2.3 and 3.2).
#include <vector>

#include "tsr/temporal/pca_basis.hpp"

namespace tsr::temporal {

struct TruncationRule {
  double epsilon = 0.005;        // unexplained fraction allowed
  double epsilonChange = 0.001;  // improvement by one more mode below which it is noise
  // Measure the noise instead of assuming it is below epsilonChange: Monte
  // Carlo noise, independent from frame to frame, adds about the same
  // energy to every centred mode, so the median mode energy is its level.
  // Each mode then counts only with what it holds beyond that level.
  bool noiseAware = true;
};

// 2.3: the lowest x >= 1 with unexplained[x] <= epsilon and unexplained[x] -
// unexplained[x + 1] <= epsilonChange (x = modes counts as no change).
// `unexplained` holds x = 0..N, as PcaBasis gives it. Noise-aware (with at
// least 4 centred modes to measure it on): with n the median energy of the
// centred modes 2..N, unexplained[x] less the (N - x) n of noise the
// dropped modes hold must be <= epsilon, and mode x + 1 must hold no more
// than max(epsilonChange, n) beyond n: keeping it would add more noise
// than it brings back.
int truncationFor(const std::vector<double>& unexplained, const TruncationRule& rule);
// The same with the noise level (an energy fraction per mode) given.
int truncationFor(const std::vector<double>& unexplained, const TruncationRule& rule, double noise);

// 3.2: the rule per pixel, smoothed by a Gaussian of `sigma` pixels (0:
// none) into a floating-point map (one value per pixel, 1..N). Noise-aware,
// a pixel's noise level is its mean energy per mode beyond the whole
// frame's M, smoothed over a Gaussian of max(sigma, 2) pixels.
std::vector<float> truncationMap(const PcaBasis& basis, const TruncationRule& rule, double sigma);

// 3.2's importance sampling: alpha = (m - mMin) / (mMax - mMin) clamped to
// [0, 1] blends each pixel from the basis reconstruction to a render with
// more samples; pixels at or under mMin keep the reconstruction.
Frame blendHighSamples(const Frame& reconstructed, const Frame& highSamples, const std::vector<float>& truncation,
                       float mMin, float mMax);

// Pixels whose m exceeds mMin: those the high-sample render must cover.
std::vector<bool> needsHighSamples(const std::vector<float>& truncation, float mMin);

}  // namespace tsr::temporal
