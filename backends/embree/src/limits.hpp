#pragma once
// What this back-end can trace: coordinates up to kMaxCoordinate (shared by
// every back-end, tsr/backend/limits.hpp says why), and rays whose origin
// and direction stay within Embree's FLT_LARGE. Any ray that still is not
// traceable (composed transforms, a degenerate frustum) is dropped, never
// handed to Embree.
#include "tsr/backend/limits.hpp"

namespace tsr::embree {

using backend::kMaxCoordinate, backend::withinCoordinateLimit;
inline constexpr float kMaxRayComponent = 1.844e18f;  // Embree's FLT_LARGE (kernels/common/ray.h)

}  // namespace tsr::embree
