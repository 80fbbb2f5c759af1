#include "tsr/sg/import/animation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "tsr/sg/scene.hpp"

namespace tsr::sg {
namespace {

glm::quat toQuat(const Vec4& v) { return glm::quat(v.w, v.x, v.y, v.z); }
Vec4 fromQuat(const glm::quat& q) { return Vec4(q.x, q.y, q.z, q.w); }

bool finite(const Vec4& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

// Index of the last key at or before t; t lies within [times.front(), times.back()].
std::size_t keyBefore(const std::vector<float>& times, float t) {
  auto it = std::upper_bound(times.begin(), times.end(), t);
  return static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, (it - times.begin()) - 1));
}

Vec4 hermite(const Vec4& p0, const Vec4& m0, const Vec4& p1, const Vec4& m1, float s) {
  const float s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * m1;
}

}  // namespace

Mat4 Animation::Pose::matrix() const {
  return glm::translate(Mat4(1.0f), translation) * glm::mat4_cast(rotation) * glm::scale(Mat4(1.0f), scale);
}

void Animation::setRestPose(ContainerId target, const Pose& pose) {
  for (Rest& r : rest_)
    if (r.target == target) {
      r.pose = pose;
      return;
    }
  rest_.push_back({target, pose});
}

void Animation::addChannel(Channel channel) {
  const std::size_t keys = channel.times.size();
  if (keys == 0) throw std::invalid_argument("animation channel has no keys");
  for (std::size_t i = 0; i < keys; ++i) {
    if (!std::isfinite(channel.times[i])) throw std::invalid_argument("animation key time is not finite");
    if (i > 0 && channel.times[i] < channel.times[i - 1])
      throw std::invalid_argument("animation key times are not ascending");
  }
  const std::size_t perKey = channel.interpolation == Interpolation::CubicSpline ? 3 : 1;
  if (channel.values.size() != keys * perKey)
    throw std::invalid_argument("animation channel has " + std::to_string(channel.values.size()) + " values for " +
                                std::to_string(keys) + " keys (expected " + std::to_string(keys * perKey) + ")");
  if (!std::all_of(channel.values.begin(), channel.values.end(), finite))
    throw std::invalid_argument("animation value is not finite");
  if (std::none_of(rest_.begin(), rest_.end(), [&](const Rest& r) { return r.target == channel.target; }))
    rest_.push_back({channel.target, Pose{}});
  channels_.push_back(std::move(channel));
}

std::vector<ContainerId> Animation::targets() const {
  std::vector<ContainerId> out;
  for (const Rest& r : rest_) out.push_back(r.target);
  return out;
}

float Animation::duration() const {
  float end = 0.0f;
  for (const Channel& c : channels_) end = std::max(end, c.times.back());
  return end;
}

float Animation::localTime(float t) const {
  const float d = duration();
  if (!std::isfinite(t)) return 0.0f;
  if (looping_ && d > 0.0f) {
    t = std::fmod(t, d);
    return t < 0.0f ? t + d : t;
  }
  return t;
}

Vec4 Animation::sample(const Channel& c, float t) {
  const bool cubic = c.interpolation == Interpolation::CubicSpline;
  auto value = [&](std::size_t key) { return cubic ? c.values[3 * key + 1] : c.values[key]; };
  if (c.times.size() == 1 || t <= c.times.front()) return value(0);
  if (t >= c.times.back()) return value(c.times.size() - 1);

  const std::size_t k = keyBefore(c.times, t);
  const float t0 = c.times[k], t1 = c.times[k + 1];
  const float dt = t1 - t0;
  const float s = dt > 0.0f ? (t - t0) / dt : 0.0f;
  const bool rotation = c.path == Path::Rotation;
  switch (c.interpolation) {
    case Interpolation::Step:
      return value(k);
    case Interpolation::Linear:
      if (rotation) return fromQuat(glm::normalize(glm::slerp(toQuat(value(k)), toQuat(value(k + 1)), s)));
      return glm::mix(value(k), value(k + 1), s);
    case Interpolation::CubicSpline: {
      const Vec4 p = hermite(c.values[3 * k + 1], dt * c.values[3 * k + 2], c.values[3 * (k + 1) + 1],
                             dt * c.values[3 * (k + 1)], s);
      return rotation ? fromQuat(glm::normalize(toQuat(p))) : p;
    }
  }
  return value(k);
}

Animation::Pose Animation::poseAt(ContainerId target, float t) const {
  Pose pose;
  for (const Rest& r : rest_)
    if (r.target == target) pose = r.pose;
  const float local = localTime(t);
  for (const Channel& c : channels_) {
    if (c.target != target) continue;
    const Vec4 v = sample(c, local);
    switch (c.path) {
      case Path::Translation:
        pose.translation = Vec3(v);
        break;
      case Path::Rotation:
        pose.rotation = toQuat(v);
        break;
      case Path::Scale:
        pose.scale = Vec3(v);
        break;
    }
  }
  return pose;
}

std::size_t Animation::apply(Scene& scene, float t, float dt) const {
  std::size_t written = 0;
  for (const Rest& r : rest_) {
    Transform* transform = scene.find<Transform>(r.target);
    if (!transform) continue;
    const Mat4 now = poseAt(r.target, t).matrix();
    transform->setMatrix(now);
    Mat4 motion(1.0f);
    if (dt > 0.0f && std::abs(glm::determinant(now)) > 1e-20f) {
      motion = poseAt(r.target, t + dt).matrix() * glm::inverse(now);
      for (int c = 0; c < 4; ++c)
        for (int k = 0; k < 4; ++k)
          if (!std::isfinite(motion[c][k])) motion = Mat4(1.0f);
    }
    if (transform->frameMotion() != motion) transform->setFrameMotion(motion);  // a still node stays unedited
    ++written;
  }
  return written;
}

}  // namespace tsr::sg
