#include "projection.hpp"

#include <cmath>
#include <limits>

namespace tsr::vk {

glm::mat4 projection(const Camera& camera, const Region& region) {
  // The sub-window of the region, with pixel edges at the same window
  // coordinates as in the full image.
  const double sx = double(camera.right - camera.left) / region.width;
  const double sy = double(camera.top - camera.bottom) / region.height;
  const double l = camera.left + sx * region.x0, r = camera.left + sx * region.x1;
  const double t = camera.top - sy * region.y0, b = camera.top - sy * region.y1;
  const double n = camera.near, f = camera.far;
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

float linearDepth(const Camera& camera, float stored) {
  if (!(stored > 0.0f)) return std::numeric_limits<float>::infinity();
  const double n = camera.near, f = camera.far;
  return float(n * f / (double(stored) * (f - n) + n));
}

glm::vec4 viewportOf(const glm::mat4& projection, std::uint32_t w, std::uint32_t h) {
  // Clip x is projection[0][0] * camera x (plus a shift for off-axis
  // regions), and a pixel is 2 / w of clip x over clip w (the depth).
  const auto spread = [](float scale, std::uint32_t pixels) {
    return scale != 0.0f && pixels > 0 ? float(2.0 / (std::abs(double(scale)) * pixels)) : 0.0f;
  };
  return {float(w), float(h), spread(projection[0][0], w), spread(projection[1][1], h)};
}

}  // namespace tsr::vk
