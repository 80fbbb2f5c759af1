#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace tsr::embree {

// A simplified visible-difference predictor in the spirit of the Animation
// Quality Metric (Myszkowski et al. 2001, after Daly's VDP), for the
// photon-count stopping rule. Steps:
//  1. band-pass decomposition by differences of Gaussians (sigma 2^k px,
//     band k centred near pixelsPerDegree / 2^(k+2) cycles per degree);
//  2. local band contrast: band / adaptation luminance, the mean of both
//     images blurred over about one degree (floored);
//  3. contrast sensitivity: Mannos-Sakrison CSF at the band's frequency,
//     scaled so its peak detects peakSensitivity^-1 contrast;
//  4. masking: the threshold rises as (S |C_mask|)^maskingSlope where the
//     weaker of the two images' band contrasts exceeds one threshold;
//  5. Minkowski pooling over bands (exponent 4) into JNDs per pixel.
// Left out of the AQM: its temporal channels (spatio-velocity CSF, eye
// tracking, temporal masking), the photoreceptor amplitude non-linearity,
// orientation-selective cortex bands, colour (luminance only), and the
// psychometric probability summation (a hard 1-JND threshold instead).
struct VisibleDifferenceSettings {
  float pixelsPerDegree = 30.0f;   // viewing geometry: about 17 degrees across 512 px
  float peakSensitivity = 100.0f;  // 1% contrast is just visible at the CSF's peak
  float maskingSlope = 0.7f;       // Daly's threshold-elevation exponent
  float adaptationFloor = 1e-3f;   // adaptation luminance floor (image units)
  void validate() const;           // throws Error
};

struct VisibleDifference {
  float fractionVisible = 0.0f;  // pixels above one JND (the AQM's d)
  float meanJnd = 0.0f;
  std::vector<float> jnd;  // per pixel, row-major
};

// a and b: luminance images of width x height, row-major, non-negative.
VisibleDifference predictVisibleDifference(std::span<const float> a, std::span<const float> b, std::uint32_t width,
                                           std::uint32_t height, const VisibleDifferenceSettings& settings = {});

}  // namespace tsr::embree
