#pragma once
// Keyframed node animation (glTF's translation, rotation and scale
// channels). It holds, per animated Transform, the rest pose and the
// channels, and writes sampled poses through Transform::setMatrix so they
// travel in the change list like any other edit.
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "tsr/sg/types.hpp"

namespace tsr::sg {

class Scene;

class Animation {
 public:
  enum class Path : std::uint8_t { Translation, Rotation, Scale };
  enum class Interpolation : std::uint8_t { Linear, Step, CubicSpline };

  struct Pose {
    Vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z
    Vec3 scale{1.0f};
    Mat4 matrix() const;
  };

  // Values are xyz (w unused) for translation and scale, xyzw quaternions
  // for rotation. CubicSpline holds (in-tangent, value, out-tangent) per key.
  struct Channel {
    ContainerId target = kNoContainer;
    Path path = Path::Translation;
    Interpolation interpolation = Interpolation::Linear;
    std::vector<float> times;
    std::vector<Vec4> values;
  };

  explicit Animation(std::string name = {}) : name_(std::move(name)) {}

  const std::string& name() const { return name_; }
  // Looping animations wrap time into [0, duration); others clamp to their keys.
  bool looping() const { return looping_; }
  void setLooping(bool on) { looping_ = on; }

  // The pose a target has where no channel animates a property.
  void setRestPose(ContainerId target, const Pose& pose);
  // Throws std::invalid_argument for keys that are not ascending and
  // finite or a value count that does not fit the interpolation.
  void addChannel(Channel channel);

  const std::vector<Channel>& channels() const { return channels_; }
  std::vector<ContainerId> targets() const;
  float duration() const;

  // A channel's value at time t (clamped to its first and last key).
  static Vec4 sample(const Channel& channel, float t);
  // The pose of a target at time t.
  Pose poseAt(ContainerId target, float t) const;
  // Writes every target's matrix at time t and, with a frame interval dt,
  // its motion over [t, t + dt] (Transform::frameMotion(), for a shutter
  // to blur; the identity when dt is 0 or the pose at t has no inverse).
  // Targets no longer in the scene are skipped. Returns the number of
  // Transforms written.
  std::size_t apply(Scene& scene, float t, float dt = 0.0f) const;

 private:
  struct Rest {
    ContainerId target;
    Pose pose;
  };
  float localTime(float t) const;

  std::string name_;
  bool looping_ = false;
  std::vector<Rest> rest_;
  std::vector<Channel> channels_;
};

}  // namespace tsr::sg
