#pragma once
// Registers the coverage renderer under the back-end name "coverage": which
// objects the view shows and how many pixels each covers, occlusion
// included (the culling service of the dissertation's section 5.4.3).
//
// Object ids: every geometry instance is reported as the scene id of the
// nearest Transform above it on its path (the node a user placed and
// named), or as the Geometry's own id when no Transform is above it.
// Instances of one Transform add up. Ids of 2^32 and above are skipped.
//
// Transparency: an instance is transparent when its material is a
// SurfaceMaterial with opacity < 1 or transmission > 0.5, or a
// SimpleMaterial with transparency > 0. Transparent instances neither
// occlude nor count: pixels behind them report what lies further back.
//
// Frame buffer: colour = a stable false colour per id (alpha 1), black with
// alpha 0 on the background; depth = camera-space depth of the visible
// surface (+inf on the background); outputs["id"] = the id, see ranking.hpp.
// Viewport parameters: threads (0 = all; viewports with the same root and
// thread count share one converted scene); engine: "embree" (default, rays
// through pixel centres) or "vulkan" (the rasterizer's id pass, sampled at
// the same pixel centres; in builds with backends/vulkan).
#include "tsr/med/viewport_registry.hpp"

namespace tsr::med {

void registerCoverage(ViewportRegistry& registry);

}  // namespace tsr::med
