#pragma once
// A camera, a node of the graph: a pinhole, or a thin lens when its
// aperture radius is above 0 (focused at focusDistance along the view). The pose maps camera space to its
// parent's space (to world space for a camera no node holds; see
// node_world.hpp for the world pose); the camera looks down its -Z axis with
// +Y up (glTF's convention). Tiles and eyes are derived from it by the
// mediators as off-axis frusta.
#include "tsr/sg/container_of.hpp"

namespace tsr::sg {

class Camera final : public ContainerOf<Camera, ContainerType::Camera> {
 public:
  enum Field : FieldIndex {
    Pose = kFirstOwnField,
    VerticalFov,
    Near,
    Far,
    EyeSeparation,
    ZeroParallax,
    ApertureRadius,
    FocusDistance,
    ShutterOpen,
    ShutterClose
  };

  const Mat4& pose() const { return pose_; }
  float verticalFov() const { return verticalFov_; }  // radians
  float nearPlane() const { return near_; }
  float farPlane() const { return far_; }
  float eyeSeparation() const { return eyeSeparation_; }        // scene units between the eyes
  float zeroParallaxDistance() const { return zeroParallax_; }  // distance of the screen plane
  // The thin lens: radius of the aperture in scene units (0: a pinhole) and
  // the distance along the view of the plane in focus.
  float apertureRadius() const { return apertureRadius_; }
  float focusDistance() const { return focusDistance_; }
  // The shutter, as fractions of the frame interval: the image integrates
  // the scene from shutterOpen to shutterClose, so what moves during that
  // time (Transform::motion()) is blurred. Equal: an instant (no blur).
  float shutterOpen() const { return shutterOpen_; }
  float shutterClose() const { return shutterClose_; }

  void setPose(const Mat4& m) { set<&Camera::pose_>(m); }
  void setVerticalFov(float v) { set<&Camera::verticalFov_>(v); }
  void setNearPlane(float v) { set<&Camera::near_>(v); }
  void setFarPlane(float v) { set<&Camera::far_>(v); }
  void setEyeSeparation(float v) { set<&Camera::eyeSeparation_>(v); }
  void setZeroParallaxDistance(float v) { set<&Camera::zeroParallax_>(v); }
  void setApertureRadius(float v) { set<&Camera::apertureRadius_>(v); }
  void setFocusDistance(float v) { set<&Camera::focusDistance_>(v); }
  void setShutterOpen(float v) { set<&Camera::shutterOpen_>(v); }
  void setShutterClose(float v) { set<&Camera::shutterClose_>(v); }

  // Points the camera from `eye` at `target`.
  void lookAt(const Vec3& eye, const Vec3& target, const Vec3& up = Vec3(0, 1, 0));

  static constexpr auto fieldSpecs() {
    using M = Camera;
    return std::tuple{valueField(Pose, "pose", &M::pose_, &M::setPose),
                      valueField(VerticalFov, "verticalFov", &M::verticalFov_, &M::setVerticalFov),
                      valueField(Near, "near", &M::near_, &M::setNearPlane),
                      valueField(Far, "far", &M::far_, &M::setFarPlane),
                      valueField(EyeSeparation, "eyeSeparation", &M::eyeSeparation_, &M::setEyeSeparation),
                      valueField(ZeroParallax, "zeroParallaxDistance", &M::zeroParallax_, &M::setZeroParallaxDistance),
                      valueField(ApertureRadius, "apertureRadius", &M::apertureRadius_, &M::setApertureRadius),
                      valueField(FocusDistance, "focusDistance", &M::focusDistance_, &M::setFocusDistance),
                      valueField(ShutterOpen, "shutterOpen", &M::shutterOpen_, &M::setShutterOpen),
                      valueField(ShutterClose, "shutterClose", &M::shutterClose_, &M::setShutterClose)};
  }

 private:
  Mat4 pose_{1.0f};
  float verticalFov_ = 0.7853982f;
  float near_ = 0.1f;
  float far_ = 1000.0f;
  float eyeSeparation_ = 0.065f;
  float zeroParallax_ = 5.0f;
  float apertureRadius_ = 0.0f;
  float focusDistance_ = 5.0f;
  float shutterOpen_ = 0.0f;
  float shutterClose_ = 0.0f;
};

}  // namespace tsr::sg
