#include "tsr/embree/camera.hpp"

#include "tsr/embree/error.hpp"
#include "tsr/embree/limits.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <string>

namespace tsr::embree {

Camera Camera::lookAt(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up, float fovY, float aspect) {
  if (!(fovY > 0.0f && fovY < 3.14159f)) throw Error("camera fovY must be in (0, pi)");
  if (!(aspect > 0.0f) || !std::isfinite(aspect)) throw Error("camera aspect must be positive");
  Camera c;
  c.cameraToWorld = glm::inverse(glm::lookAt(eye, target, up));
  c.top = std::tan(0.5f * fovY);
  c.bottom = -c.top;
  c.right = c.top * aspect;
  c.left = -c.right;
  c.near = 1.0f;
  c.validate();
  return c;
}

namespace {
void validatePose(const glm::mat4& pose, const char* what) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (!withinCoordinateLimit(pose[i][j]))
        throw Error(std::string(what) + " entry " + std::to_string(pose[i][j]) +
                    " is NaN, infinite or beyond 1e12 (kMaxCoordinate)" + (i == 3 ? ": the eye cannot be traced" : ""));
  if (std::abs(glm::determinant(glm::mat3(pose))) < 1e-12f) throw Error(std::string(what) + " is singular");
}
}  // namespace

void Camera::validate() const {
  validatePose(cameraToWorld, "camera transform");
  if (cameraToWorldAtEnd) validatePose(*cameraToWorldAtEnd, "camera transform at the frame's end");
  if (!withinCoordinateLimit(left) || !withinCoordinateLimit(right) || !withinCoordinateLimit(bottom) ||
      !withinCoordinateLimit(top) || !withinCoordinateLimit(near)) {
    throw Error("camera frustum contains NaN, infinity or a value beyond 1e12 (kMaxCoordinate)");
  }
  if (!(left < right) || !(bottom < top)) throw Error("camera window is empty (need left < right, bottom < top)");
  if (!(near > 0.0f)) throw Error("camera near must be positive");
  if (!(apertureRadius >= 0.0f) || !withinCoordinateLimit(apertureRadius))
    throw Error("camera aperture radius must be finite and not negative");
  if (!(focusDistance > 0.0f) || !withinCoordinateLimit(focusDistance))
    throw Error("camera focus distance must be finite and positive");
  if (!(shutterOpen >= 0.0f && shutterOpen <= shutterClose && shutterClose <= 1.0f))
    throw Error("camera shutter [" + std::to_string(shutterOpen) + ", " + std::to_string(shutterClose) +
                "] must lie in [0, 1] and open before it closes");
}

}  // namespace tsr::embree
