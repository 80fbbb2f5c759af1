#pragma once
// The viewer's navigation: a camera orbiting a target point, with pan, zoom
// and fly moves. It holds its own pose (target, distance, yaw, pitch) and
// writes the scene camera through Camera::lookAt only when a move changes
// it, so an untouched viewer shows exactly the scene's camera.
#include <glm/vec3.hpp>

#include "tsr/sg/camera.hpp"

namespace tsr::app {

class OrbitCamera {
 public:
  // Takes eye and viewing direction from the camera's pose; the target is
  // on the viewing axis at the distance of `centre` (the scene's bounds'
  // centre) along it, or `radius` ahead when that is behind the camera.
  void reset(const sg::Camera& camera, const glm::vec3& centre, float radius);
  // Looks at the bounds from the front (+Z), the whole sphere in view.
  void frame(const glm::vec3& centre, float radius, float verticalFov);

  void orbit(float yawDegrees, float pitchDegrees);
  // Moves eye and target by fractions of the view's height at the target.
  void pan(float dx, float dy, float verticalFov);
  void zoom(float factor);  // distance times factor
  // Moves eye and target along the view axes by fractions of the scene radius.
  void fly(float forward, float right, float up);

  glm::vec3 eye() const;
  glm::vec3 target() const { return target_; }
  float distance() const { return distance_; }
  float yawDegrees() const { return yaw_; }
  float pitchDegrees() const { return pitch_; }
  void set(const glm::vec3& target, float distance, float yawDegrees, float pitchDegrees);

  // Writes the pose into `camera` (lookAt, near and far from the radius)
  // when it changed since the last apply or reset; true if it wrote.
  bool apply(sg::Camera& camera);

 private:
  glm::vec3 direction() const;  // from target to eye

  glm::vec3 target_{0.0f};
  float distance_ = 1.0f, yaw_ = 0.0f, pitch_ = 0.0f, radius_ = 1.0f;
  bool changed_ = false;
};

}  // namespace tsr::app
