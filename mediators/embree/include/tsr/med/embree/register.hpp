#pragma once
// Registers the Embree path tracer under the back-end name "embree".
// Viewport parameters: spp (samples per pixel to reach, default 16),
// maxDepth (scattering events, default 8), seed (default 0), threads
// (0 = all), samplesPerPass (default: passes of 1, 2, 4, then 8 samples),
// directOnly (bool: maxDepth 1). temporal = "photons" makes a photon
// animation viewport instead (src/photon_viewport.hpp: its own scenes, a
// lookahead, and the photon parameters listed there).
#include "tsr/med/viewport_registry.hpp"

namespace tsr::med {

void registerEmbree(ViewportRegistry& registry);

}  // namespace tsr::med
