#include "tsr/vk/camera.hpp"

#include "tsr/vk/error.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <limits>

namespace tsr::vk {

Camera Camera::lookAt(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up, float fovY, float aspect,
                      float near, float far) {
  if (!(fovY > 0.0f && fovY < 3.14159f)) throw Error("camera fovY must be in (0, pi)");
  if (!(aspect > 0.0f) || !std::isfinite(aspect)) throw Error("camera aspect must be positive");
  Camera c;
  c.cameraToWorld = glm::inverse(glm::lookAt(eye, target, up));
  c.near = near;
  c.far = far;
  c.top = near * std::tan(0.5f * fovY);
  c.bottom = -c.top;
  c.right = c.top * aspect;
  c.left = -c.right;
  c.validate();
  return c;
}

void Camera::validate() const {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (!std::isfinite(cameraToWorld[i][j])) throw Error("camera transform contains NaN or infinity");
  if (!std::isfinite(left) || !std::isfinite(right) || !std::isfinite(bottom) || !std::isfinite(top) ||
      !std::isfinite(near) || !std::isfinite(far)) {
    throw Error("camera frustum contains NaN or infinity");
  }
  if (!(left < right) || !(bottom < top)) throw Error("camera window is empty (need left < right, bottom < top)");
  if (!(near > 0.0f)) throw Error("camera near must be positive");
  if (!(far > near)) throw Error("camera far must be greater than near");
  if (std::abs(glm::determinant(glm::mat3(cameraToWorld))) < 1e-12f) throw Error("camera transform is singular");
}

glm::mat4 Camera::projection(const Region& region) const {
  // The sub-window of the region, with pixel edges at the same window
  // coordinates as in the full image.
  const double sx = double(right - left) / region.width;
  const double sy = double(top - bottom) / region.height;
  const double l = left + sx * region.x0, r = left + sx * region.x1;
  const double t = top - sy * region.y0, b = top - sy * region.y1;
  const double n = near, f = far;
  glm::dmat4 p(0.0);
  p[0][0] = 2.0 * n / (r - l);
  p[2][0] = (r + l) / (r - l);
  // Vulkan's clip-space y points down; the image's rows go down too.
  p[1][1] = -2.0 * n / (t - b);
  p[2][1] = -(t + b) / (t - b);
  // Reversed depth: z_ndc = n (f - d) / (d (f - n)) for view depth d = -z.
  p[2][2] = n / (f - n);
  p[3][2] = n * f / (f - n);
  p[2][3] = -1.0;
  return glm::mat4(p);
}

glm::mat4 Camera::worldToCamera() const { return glm::inverse(cameraToWorld); }

float Camera::linearDepth(float stored) const {
  if (!(stored > 0.0f)) return std::numeric_limits<float>::infinity();
  const double n = near, f = far;
  return float(n * f / (double(stored) * (f - n) + n));
}

}  // namespace tsr::vk
