#pragma once
// Small blurs of one image plane (row-major, width w, height h) shared by
// the filters; both clamp their footprint at the image's border.
#include <vector>

namespace tsr::embree::pf {

// The mean over the (2 radius + 1)^2 box around each pixel, separable.
std::vector<float> boxMean(const std::vector<float>& in, int w, int h, int radius);

// 1-2-1 by 1-2-1 weights over 3x3 pixels (SVGF's variance prefilter: a
// single pixel's estimate of its variance is itself noisy). threads: TBB
// workers, 0 = all; the result does not depend on them.
std::vector<float> blur121(const std::vector<float>& in, int w, int h, int threads = 0);

}  // namespace tsr::embree::pf
