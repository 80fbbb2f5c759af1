#pragma once

#include "tsr/vk/region.hpp"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace tsr::vk {

// Pinhole camera with an arbitrary off-axis frustum, the same convention as
// the Embree back-end: in camera space the eye is at the origin looking down
// -Z with +Y up; the image is the window [left, right] x [bottom, top] on the
// plane z = -near. Rasterization also clips at z = -far.
struct Camera {
  glm::mat4 cameraToWorld{1.0f};
  float left = -1.0f;
  float right = 1.0f;
  float bottom = -1.0f;
  float top = 1.0f;
  float near = 1.0f;
  float far = 1000.0f;

  // Symmetric frustum; fovY is the full vertical angle in radians.
  static Camera lookAt(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up, float fovY, float aspect,
                       float near = 0.1f, float far = 1000.0f);

  // Throws Error on non-finite values, an empty window, near <= 0 or far <= near.
  void validate() const;

  // Vulkan clip-space projection of the sub-window that `region` cuts out of
  // the full image (off-axis), with reversed depth: near -> 1, far -> 0.
  glm::mat4 projection(const Region& region) const;
  glm::mat4 worldToCamera() const;

  // Camera-space depth (distance along the view axis) for a stored depth
  // value of projection(); +infinity for 0 (the cleared far value).
  float linearDepth(float storedDepth) const;

  bool operator==(const Camera&) const = default;
};

}  // namespace tsr::vk
