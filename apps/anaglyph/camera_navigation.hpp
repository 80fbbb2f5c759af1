#pragma once
// Mouse and keyboard navigation of a camera pose, as in model viewers: orbit
// about a target point, pan, dolly towards the target, fly. The pose maps
// camera space to world space (camera looking down -Z, +Y up); world +Y
// stays up.
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace tsr::app {

class CameraNavigation {
 public:
  // `targetDistance`: how far ahead of the camera the orbit centre lies.
  CameraNavigation(const glm::mat4& pose, float targetDistance);

  // Degrees about world +Y (yaw) and the camera's x axis (pitch, kept
  // within ±89° of the horizon).
  void orbit(float yawDegrees, float pitchDegrees);
  // Moves camera and target across the view, in fractions of the target distance.
  void pan(float right, float up);
  // Positive steps move towards the target (each 10 % of the distance left).
  void dolly(float steps);
  // Moves camera and target in camera space, in fractions of the target distance.
  void fly(const glm::vec3& cameraSpace);

  glm::mat4 pose() const;
  glm::vec3 eye() const { return eye_; }
  glm::vec3 target() const { return target_; }

 private:
  glm::vec3 eye_, target_;
};

}  // namespace tsr::app
