#include "camera_navigation.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace tsr::app {

namespace {
const glm::vec3 kUp(0, 1, 0);
}

CameraNavigation::CameraNavigation(const glm::mat4& pose, float targetDistance) {
  eye_ = glm::vec3(pose[3]);
  const glm::vec3 forward = -glm::normalize(glm::vec3(pose[2]));
  target_ = eye_ + forward * std::max(targetDistance, 1e-4f);
}

void CameraNavigation::orbit(float yawDegrees, float pitchDegrees) {
  glm::vec3 offset = eye_ - target_;
  const float radius = glm::length(offset);
  float yaw = std::atan2(offset.x, offset.z) + glm::radians(yawDegrees);
  float pitch = std::asin(std::clamp(offset.y / radius, -1.0f, 1.0f)) + glm::radians(pitchDegrees);
  pitch = std::clamp(pitch, glm::radians(-89.0f), glm::radians(89.0f));
  offset = radius * glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
  eye_ = target_ + offset;
}

void CameraNavigation::pan(float right, float up) {
  const glm::mat4 p = pose();
  const float distance = glm::length(target_ - eye_);
  const glm::vec3 move = (glm::vec3(p[0]) * right + glm::vec3(p[1]) * up) * distance;
  eye_ += move;
  target_ += move;
}

void CameraNavigation::dolly(float steps) {
  const float factor = std::pow(0.9f, steps);
  const glm::vec3 offset = eye_ - target_;
  if (glm::length(offset) * factor > 1e-4f) eye_ = target_ + offset * factor;
}

void CameraNavigation::fly(const glm::vec3& cameraSpace) {
  const glm::mat4 p = pose();
  const float distance = glm::length(target_ - eye_);
  const glm::vec3 move = glm::mat3(p) * cameraSpace * distance;
  eye_ += move;
  target_ += move;
}

glm::mat4 CameraNavigation::pose() const { return glm::inverse(glm::lookAt(eye_, target_, kUp)); }

}  // namespace tsr::app
