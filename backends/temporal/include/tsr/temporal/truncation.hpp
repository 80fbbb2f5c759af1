#pragma once
// How many PCA modes to keep (Meyer & Anderson 2.3 and 3.2).
#include <vector>

#include "tsr/temporal/pca_basis.hpp"

namespace tsr::temporal {

struct TruncationRule {
  double epsilon = 0.005;        // unexplained fraction allowed
  double epsilonChange = 0.001;  // improvement by one more mode below which it is noise
};

// 2.3: the lowest x >= 1 with unexplained[x] <= epsilon and unexplained[x] -
// unexplained[x + 1] <= epsilonChange (x = modes counts as no change).
// `unexplained` holds x = 0..N, as PcaBasis gives it.
int truncationFor(const std::vector<double>& unexplained, const TruncationRule& rule);

// 3.2: the rule per pixel, smoothed by a Gaussian of `sigma` pixels (0:
// none) into a floating-point map (one value per pixel, 1..N).
std::vector<float> truncationMap(const PcaBasis& basis, const TruncationRule& rule, double sigma);

// 3.2's importance sampling: alpha = (m - mMin) / (mMax - mMin) clamped to
// [0, 1] blends each pixel from the basis reconstruction to a render with
// more samples; pixels at or under mMin keep the reconstruction.
Frame blendHighSamples(const Frame& reconstructed, const Frame& highSamples, const std::vector<float>& truncation,
                       float mMin, float mMax);

// Pixels whose m exceeds mMin: those the high-sample render must cover.
std::vector<bool> needsHighSamples(const std::vector<float>& truncation, float mMin);

}  // namespace tsr::temporal
