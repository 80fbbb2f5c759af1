#include "orbit_camera.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include "tsr/sg/node_world.hpp"

namespace tsr::app {

namespace {
constexpr float kMaxPitch = 89.0f;  // lookAt with +Y up degenerates at the poles
}

void OrbitCamera::reset(const sg::Camera& camera, const glm::vec3& centre, float radius) {
  const glm::mat4 pose = sg::cameraWorldPose(camera);  // navigation is in world space
  const glm::vec3 eye(pose[3]);
  const glm::vec3 forward = glm::normalize(-glm::vec3(pose[2]));
  radius_ = std::max(radius, 1e-4f);
  float along = glm::dot(centre - eye, forward);
  if (!(along > radius_ * 0.1f)) along = radius_;
  distance_ = along;
  target_ = eye + forward * along;
  const glm::vec3 back = -forward;  // target to eye
  pitch_ = glm::degrees(std::asin(std::clamp(back.y, -1.0f, 1.0f)));
  yaw_ = glm::degrees(std::atan2(back.x, back.z));
  changed_ = false;
}

void OrbitCamera::frame(const glm::vec3& centre, float radius, float verticalFov) {
  radius_ = std::max(radius, 1e-4f);
  target_ = centre;
  distance_ = radius_ / std::sin(verticalFov * 0.5f);
  yaw_ = 0.0f;
  pitch_ = 0.0f;
  changed_ = true;
}

glm::vec3 OrbitCamera::direction() const {
  const float y = glm::radians(yaw_), p = glm::radians(pitch_);
  return {std::cos(p) * std::sin(y), std::sin(p), std::cos(p) * std::cos(y)};
}

glm::vec3 OrbitCamera::eye() const { return target_ + direction() * distance_; }

void OrbitCamera::set(const glm::vec3& target, float distance, float yawDegrees, float pitchDegrees) {
  target_ = target;
  distance_ = std::max(distance, radius_ * 1e-3f);
  yaw_ = std::fmod(yawDegrees, 360.0f);
  pitch_ = std::clamp(pitchDegrees, -kMaxPitch, kMaxPitch);
  changed_ = true;
}

void OrbitCamera::orbit(float yawDegrees, float pitchDegrees) {
  if (yawDegrees == 0.0f && pitchDegrees == 0.0f) return;
  set(target_, distance_, yaw_ + yawDegrees, pitch_ + pitchDegrees);
}

void OrbitCamera::pan(float dx, float dy, float verticalFov) {
  if (dx == 0.0f && dy == 0.0f) return;
  const glm::vec3 back = direction();
  const glm::vec3 right = glm::normalize(glm::cross(glm::vec3(0, 1, 0), back));
  const glm::vec3 up = glm::cross(back, right);
  const float height = 2.0f * distance_ * std::tan(verticalFov * 0.5f);
  target_ += (right * dx + up * dy) * height;
  changed_ = true;
}

void OrbitCamera::zoom(float factor) {
  if (factor == 1.0f || !(factor > 0.0f)) return;
  distance_ = std::max(distance_ * factor, radius_ * 1e-3f);
  changed_ = true;
}

void OrbitCamera::fly(float forward, float right, float up) {
  if (forward == 0.0f && right == 0.0f && up == 0.0f) return;
  const glm::vec3 back = direction();
  const glm::vec3 r = glm::normalize(glm::cross(glm::vec3(0, 1, 0), back));
  target_ += (-back * forward + r * right + glm::vec3(0, 1, 0) * up) * radius_;
  changed_ = true;
}

bool OrbitCamera::apply(sg::Camera& camera) {
  if (!changed_) return false;
  changed_ = false;
  sg::setCameraWorldPose(camera, glm::inverse(glm::lookAt(eye(), target_, glm::vec3(0, 1, 0))));
  // Near and far bracket the scene from wherever the eye went.
  const float reach = distance_ + radius_ * 4.0f + glm::length(target_);
  camera.setNearPlane(std::max(std::min(distance_ * 1e-3f, radius_ * 1e-3f), 1e-5f));
  camera.setFarPlane(std::max(reach * 2.0f, camera.nearPlane() * 10.0f));
  return true;
}

}  // namespace tsr::app
