#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace tsr::cov {

// Pinhole camera with an arbitrary off-axis frustum, the same convention as
// the path tracer's: in camera space the eye is at the origin looking down
// -Z with +Y up; the FULL image is the window [left, right] x [bottom, top]
// on the plane z = -near. Tiles and eyes are regions or other windows.
struct Camera {
  glm::mat4 cameraToWorld{1.0f};
  float left = -1.0f;
  float right = 1.0f;
  float bottom = -1.0f;
  float top = 1.0f;
  float near = 1.0f;

  // Symmetric frustum; fovY is the full vertical angle in radians.
  static Camera lookAt(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up, float fovY, float aspect);

  // Throws Error on non-finite values, an empty window, near <= 0 or a
  // singular transform.
  void validate() const;

  bool operator==(const Camera&) const = default;
};

}  // namespace tsr::cov
