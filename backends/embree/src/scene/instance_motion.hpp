#pragma once
// An instance moving over the frame interval, as Embree interpolates it:
// each end's matrix split into a translation, a rotation and an upper
// triangular scale-and-shear (M = T R S), the translation and S blended
// linearly and the rotation along the shortest arc (slerp). A turning
// object keeps its size mid-frame, which blending the matrices would not.
#include <embree3/rtcore.h>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

namespace tsr::embree {

class InstanceMotion {
 public:
  InstanceMotion(const glm::mat4& start, const glm::mat4& end);

  // The instance's transform at ray time t in [0, 1].
  glm::mat4 at(float t) const;
  // The decomposition of time step 0 or 1, for rtcSetGeometryTransformQuaternion.
  RTCQuaternionDecomposition step(int i) const;

 private:
  struct Pose {
    glm::vec3 translation;
    glm::quat rotation;
    glm::mat3 scaleShear;  // upper triangular
  };
  static Pose decompose(const glm::mat4& m);

  Pose ends_[2];
};

}  // namespace tsr::embree
