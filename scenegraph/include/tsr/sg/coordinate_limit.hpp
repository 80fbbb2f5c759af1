#pragma once
// The largest coordinate the scene graph accepts for what back-ends trace:
// vertex data, transform and camera matrices. Finite is not enough: Embree
// refuses (in debug builds: aborts on) rays whose origin lies beyond
// FLT_LARGE = 1.844e18, and a ray-triangle test forms triple products of
// coordinate differences (up to 48 c^3), which overflow float (3.4e38) once
// coordinates pass about 1.9e12. 1e12 keeps both with room to spare and is still far
// beyond any scene a float renders sensibly (its spacing there is 65536).
#include <cmath>

namespace tsr::sg {

inline constexpr float kMaxCoordinate = 1e12f;

// False for NaN, infinity and magnitudes beyond kMaxCoordinate.
inline bool withinCoordinateLimit(float v) { return std::abs(v) <= kMaxCoordinate; }

}  // namespace tsr::sg
