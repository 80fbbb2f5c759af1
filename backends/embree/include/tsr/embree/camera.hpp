#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <optional>

namespace tsr::embree {

// Pinhole or thin-lens camera with an arbitrary off-axis frustum. In camera space the eye
// is at the origin looking down -Z with +Y up; the image is the window
// [left, right] x [bottom, top] on the plane z = -near. A wall tile or one
// eye of a stereo pair is just another window.
struct Camera {
  glm::mat4 cameraToWorld{1.0f};
  float left = -1.0f;
  float right = 1.0f;
  float bottom = -1.0f;
  float top = 1.0f;
  float near = 1.0f;
  // A thin lens of this radius in the eye's xy plane, focused on the plane
  // z = -focusDistance: rays through a window point start on the lens and
  // meet the pinhole ray on that plane. 0: the pinhole.
  float apertureRadius = 0.0f;
  float focusDistance = 1.0f;
  // The shutter, as fractions of the frame interval (ray times, 0 its
  // start, 1 its end): samples spread uniformly over [shutterOpen,
  // shutterClose]; equal, every ray has that one time. A camera that moves
  // is at cameraToWorldAtEnd at time 1 (interpolated linearly between).
  float shutterOpen = 0.0f;
  float shutterClose = 0.0f;
  std::optional<glm::mat4> cameraToWorldAtEnd;

  // Symmetric frustum; fovY is the full vertical angle in radians.
  static Camera lookAt(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up, float fovY, float aspect);

  // Throws Error on non-finite values or ones beyond kMaxCoordinate
  // (limits.hpp), an empty window, near <= 0, or a shutter outside
  // 0 <= open <= close <= 1.
  void validate() const;

  bool operator==(const Camera&) const = default;
};

}  // namespace tsr::embree
