#pragma once
// A View in the back-ends' shared vocabulary (backends/common): its camera
// and its region, written once for every back-end. Each back-end uses what
// it models of the camera (the rasterizer ignores the lens and the
// shutter, the id pass also the far plane).
#include "tsr/backend/camera.hpp"
#include "tsr/backend/region.hpp"
#include "tsr/med/view.hpp"

namespace tsr::med {

// Pose, window, near and far, lens, shutter and the pose at the frame's end.
backend::Camera cameraOf(const View& view);
// The full image and the rectangle of it to render.
backend::Region regionOf(const View& view);

}  // namespace tsr::med
