#include "scene/instance_motion.hpp"

#include <glm/geometric.hpp>

namespace tsr::embree {

// Gram-Schmidt on the columns of the linear part: A = Q U, Q a rotation
// (a mirror's sign goes to U's last diagonal entry), U upper triangular.
InstanceMotion::Pose InstanceMotion::decompose(const glm::mat4& m) {
  const glm::vec3 a0(m[0]), a1(m[1]), a2(m[2]);
  glm::mat3 u(0.0f);  // u[column][row]
  u[0][0] = glm::length(a0);
  const glm::vec3 q0 = a0 / u[0][0];
  u[1][0] = glm::dot(q0, a1);
  glm::vec3 q1 = a1 - u[1][0] * q0;
  u[1][1] = glm::length(q1);
  q1 /= u[1][1];
  u[2][0] = glm::dot(q0, a2);
  u[2][1] = glm::dot(q1, a2);
  glm::vec3 q2 = a2 - u[2][0] * q0 - u[2][1] * q1;
  u[2][2] = glm::length(q2);
  q2 /= u[2][2];
  if (glm::dot(glm::cross(q0, q1), q2) < 0.0f) {
    q2 = -q2;
    u[2][2] = -u[2][2];
  }
  return {glm::vec3(m[3]), glm::normalize(glm::quat_cast(glm::mat3(q0, q1, q2))), u};
}

InstanceMotion::InstanceMotion(const glm::mat4& start, const glm::mat4& end) : ends_{decompose(start), decompose(end)} {
  // The same rotation twice over: take the shorter way round.
  if (glm::dot(ends_[0].rotation, ends_[1].rotation) < 0.0f) ends_[1].rotation = -ends_[1].rotation;
}

glm::mat4 InstanceMotion::at(float t) const {
  const glm::mat3 linear = glm::mat3_cast(glm::slerp(ends_[0].rotation, ends_[1].rotation, t)) *
                           ((1.0f - t) * ends_[0].scaleShear + t * ends_[1].scaleShear);
  glm::mat4 m(linear);
  m[3] = glm::vec4((1.0f - t) * ends_[0].translation + t * ends_[1].translation, 1.0f);
  return m;
}

RTCQuaternionDecomposition InstanceMotion::step(int i) const {
  const Pose& p = ends_[i];
  RTCQuaternionDecomposition d;
  rtcInitQuaternionDecomposition(&d);
  d.scale_x = p.scaleShear[0][0];
  d.scale_y = p.scaleShear[1][1];
  d.scale_z = p.scaleShear[2][2];
  d.skew_xy = p.scaleShear[1][0];
  d.skew_xz = p.scaleShear[2][0];
  d.skew_yz = p.scaleShear[2][1];
  d.quaternion_r = p.rotation.w;
  d.quaternion_i = p.rotation.x;
  d.quaternion_j = p.rotation.y;
  d.quaternion_k = p.rotation.z;
  d.translation_x = p.translation.x;
  d.translation_y = p.translation.y;
  d.translation_z = p.translation.z;
  return d;
}

}  // namespace tsr::embree
