#pragma once
// What this back-end can trace. Embree refuses (in debug builds: aborts on)
// a ray whose origin or direction has a component beyond FLT_LARGE
// (1.844e18, embree's kernels/common/ray.h), and its triangle tests form
// triple products of coordinate differences that overflow float (3.4e38)
// once coordinates pass about 1.9e12. So cameras, instance transforms and
// vertices are refused beyond kMaxCoordinate, and any ray that still is not
// traceable (composed transforms, a degenerate frustum) is dropped, never
// handed to Embree.
#include <cmath>

namespace tsr::embree {

inline constexpr float kMaxCoordinate = 1e12f;
inline constexpr float kMaxRayComponent = 1.844e18f;  // Embree's FLT_LARGE

// False for NaN, infinity and magnitudes beyond kMaxCoordinate.
inline bool withinCoordinateLimit(float v) { return std::abs(v) <= kMaxCoordinate; }

}  // namespace tsr::embree
