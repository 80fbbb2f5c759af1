#include "tsr/backend/camera.hpp"

#include "tsr/backend/limits.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace tsr::backend {

Camera Camera::lookAt(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up, float fovY, float aspect,
                      float near, float far) {
  Camera c;
  c.cameraToWorld = glm::inverse(glm::lookAt(eye, target, up));
  c.near = near;
  c.far = far;
  c.top = near * std::tan(0.5f * fovY);
  c.bottom = -c.top;
  c.right = c.top * aspect;
  c.left = -c.right;
  return c;
}

glm::mat4 Camera::worldToCamera() const { return glm::inverse(cameraToWorld); }

namespace {
std::optional<std::string> poseProblem(const glm::mat4& pose, const char* what) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (!withinCoordinateLimit(pose[i][j]))
        return std::string(what) + " entry " + std::to_string(pose[i][j]) +
               " is NaN, infinite or beyond 1e12 (kMaxCoordinate)" + (i == 3 ? ": the eye cannot be traced" : "");
  if (std::abs(glm::determinant(glm::mat3(pose))) < 1e-12f) return std::string(what) + " is singular";
  return std::nullopt;
}
}  // namespace

std::optional<std::string> Camera::invalidReason() const {
  if (auto why = poseProblem(cameraToWorld, "camera transform")) return why;
  if (cameraToWorldAtEnd) {
    if (auto why = poseProblem(*cameraToWorldAtEnd, "camera transform at the frame's end")) return why;
  }
  for (float v : {left, right, bottom, top, near})
    if (!withinCoordinateLimit(v))
      return "camera frustum contains NaN, infinity or a value beyond 1e12 (kMaxCoordinate)";
  // Far is a depth range, not a coordinate: glTF's "infinite" far is 1e30.
  if (!std::isfinite(far)) return "camera far must be finite";
  if (!(left < right) || !(bottom < top)) return "camera window is empty (need left < right, bottom < top)";
  if (!(near > 0.0f)) return "camera near must be positive";
  if (!(far > near)) return "camera far must be greater than near";
  if (!(apertureRadius >= 0.0f) || !withinCoordinateLimit(apertureRadius))
    return "camera aperture radius must be finite and not negative";
  if (!(focusDistance > 0.0f) || !withinCoordinateLimit(focusDistance))
    return "camera focus distance must be finite and positive";
  if (!(shutterOpen >= 0.0f && shutterOpen <= shutterClose && shutterClose <= 1.0f))
    return "camera shutter [" + std::to_string(shutterOpen) + ", " + std::to_string(shutterClose) +
           "] must lie in [0, 1] and open before it closes";
  return std::nullopt;
}

}  // namespace tsr::backend
