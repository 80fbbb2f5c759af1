#pragma once
// Registers the Vulkan rasterizer under the back-end name "vulkan".
// Viewport parameters: msaa (1 or 4, default 1), shadows (bool, default
// true: shadow maps for spot and directional lights), shadowMapSize
// (16..8192, default 1024). All viewports of a process share one Vulkan
// device; viewports with the same root and background share one converted
// scene.
#include "tsr/med/viewport_registry.hpp"

namespace tsr::med {

void registerVulkan(ViewportRegistry& registry);

}  // namespace tsr::med
