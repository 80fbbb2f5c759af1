#include "tsr/cov/camera.hpp"

#include "tsr/cov/error.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace tsr::cov {

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

void Camera::validate() const {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (!std::isfinite(cameraToWorld[i][j])) throw Error("camera transform contains NaN or infinity");
  for (float v : {left, right, bottom, top, near})
    if (!std::isfinite(v)) throw Error("camera frustum contains NaN or infinity");
  if (!(left < right) || !(bottom < top)) throw Error("camera window is empty (need left < right, bottom < top)");
  if (!(near > 0.0f)) throw Error("camera near must be positive");
  if (std::abs(glm::determinant(glm::mat3(cameraToWorld))) < 1e-12f) throw Error("camera transform is singular");
}

}  // namespace tsr::cov
