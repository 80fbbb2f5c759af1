#pragma once
// The back-ends' shared vocabulary (backends/common) under the rasterizer's
// names: tsr::vk::Camera is tsr::backend::Camera, and so are Region, the
// ids and the lights. The rasterizer clips at the camera's near and far and
// ignores its lens and shutter (src/projection.hpp).
#include "tsr/backend/vocabulary.hpp"

namespace tsr::vk {
using namespace backend;
}  // namespace tsr::vk
