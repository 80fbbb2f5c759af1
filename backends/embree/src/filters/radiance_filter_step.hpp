#pragma once
// The filtering step of radiance filtering, run by Renderer::renderRadiancePass
// after the tracing step has filled the accumulator's samples. Private to
// the back-end.
#include "tsr/embree/radiance_filter.hpp"

namespace tsr::embree {

struct RadianceFilterStep {
  // Restarts acc if it belongs to another epoch of fb, then filters every
  // pixel (TBB, in the calling arena) and accumulates the estimates.
  static void run(const FrameBuffer& fb, RadianceAccumulator& acc, const RadianceFilterSettings& settings);
};

}  // namespace tsr::embree
