#pragma once
// The largest coordinate a back-end is handed. Embree refuses (in debug
// builds: aborts on) a ray whose origin or direction has a component beyond
// FLT_LARGE (1.844e18, embree's kernels/common/ray.h), and its triangle
// tests form triple products of coordinate differences that overflow float
// (3.4e38) once coordinates pass about 1.9e12; a rasterizer's float
// matrices lose every digit of a scene long before. So cameras, instance
// transforms and vertices are refused beyond kMaxCoordinate.
#include <cmath>

namespace tsr::backend {

inline constexpr float kMaxCoordinate = 1e12f;

// False for NaN, infinity and magnitudes beyond kMaxCoordinate.
inline bool withinCoordinateLimit(float v) { return std::abs(v) <= kMaxCoordinate; }

}  // namespace tsr::backend
