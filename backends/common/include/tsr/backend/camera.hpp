#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <optional>
#include <string>

namespace tsr::backend {

// The camera of every back-end: an arbitrary off-axis frustum, optionally
// with a thin lens and an open shutter. In camera space the eye is at the
// origin looking down -Z with +Y up; the FULL image is the window
// [left, right] x [bottom, top] on the plane z = -near. A wall tile or one
// eye of a stereo pair is just another window, and a Region cuts a crop
// out of it. Each back-end uses what it models: the rasterizer clips at
// near and far; the path tracer and the id pass never clip, and only the
// path tracer has a lens and a shutter.
struct Camera {
  glm::mat4 cameraToWorld{1.0f};
  float left = -1.0f;
  float right = 1.0f;
  float bottom = -1.0f;
  float top = 1.0f;
  float near = 1.0f;
  float far = 1000.0f;
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

  // Symmetric frustum: fovY is the full vertical angle in radians, the
  // window lies on the near plane. A fovY outside (0, pi) or an aspect that
  // is not positive gives an empty window, which invalidReason names.
  static Camera lookAt(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up, float fovY, float aspect,
                       float near = 0.1f, float far = 1000.0f);

  glm::mat4 worldToCamera() const;

  // Why no back-end can use it, or nothing: a pose, window or near that is
  // NaN, infinite or beyond kMaxCoordinate (limits.hpp), a singular pose,
  // an empty window, near <= 0, a far that is infinite or <= near, a
  // negative aperture, a focus distance <= 0, or a shutter outside
  // 0 <= open <= close <= 1. See validate.hpp.
  std::optional<std::string> invalidReason() const;

  bool operator==(const Camera&) const = default;
};

}  // namespace tsr::backend
