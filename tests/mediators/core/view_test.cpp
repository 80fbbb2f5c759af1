#include "tsr/med/view.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "tsr/sg/scene.hpp"

using namespace tsr;
using med::View;

namespace {
// Pixel coordinates of a world point in a view (full-image pixels).
glm::vec2 project(const View& v, const glm::vec3& world) {
  glm::vec4 c = glm::inverse(v.cameraToWorld) * glm::vec4(world, 1.0f);
  float x = -c.x / c.z * v.nearPlane, y = -c.y / c.z * v.nearPlane;
  return {(x - v.left) / (v.right - v.left) * float(v.width), (v.top - y) / (v.top - v.bottom) * float(v.height)};
}
}  // namespace

TEST(View, FromCameraMatchesFieldOfViewAndAspect) {
  sg::Scene s;
  auto& cam = s.create<sg::Camera>();
  cam.setVerticalFov(glm::radians(90.0f));
  cam.setNearPlane(2.0f);
  View v = View::fromCamera(cam, 200, 100);
  EXPECT_NEAR(v.top, 2.0f, 1e-5f);
  EXPECT_NEAR(v.right, 4.0f, 1e-5f);
  EXPECT_EQ(v.region, (med::PixelRect{0, 0, 200, 100}));
  EXPECT_NO_THROW(v.validate());
  // The optical axis hits the image centre.
  glm::vec2 p = project(v, glm::vec3(0, 0, -10));
  EXPECT_NEAR(p.x, 100.0f, 1e-3f);
  EXPECT_NEAR(p.y, 50.0f, 1e-3f);
}

TEST(View, EyesAgreeOnTheZeroParallaxPlaneOnly) {
  sg::Scene s;
  auto& cam = s.create<sg::Camera>();
  cam.lookAt({0, 0, 5}, {0, 0, 0});
  View mono = View::fromCamera(cam, 320, 240);
  View left = mono.eye(med::Eye::Left, 0.2f, 5.0f), right = mono.eye(med::Eye::Right, 0.2f, 5.0f);
  glm::vec3 onPlane(0.7f, -0.3f, 0.0f);  // 5 units in front of the camera
  EXPECT_NEAR(project(left, onPlane).x, project(right, onPlane).x, 1e-3f);
  EXPECT_NEAR(project(left, onPlane).y, project(right, onPlane).y, 1e-3f);
  glm::vec3 behind(0.7f, -0.3f, -5.0f);
  EXPECT_GT(std::abs(project(left, behind).x - project(right, behind).x), 1.0f) << "parallax behind the plane";
}

TEST(View, ValidationNamesTheProblem) {
  View v;
  EXPECT_THROW(v.validate(), std::invalid_argument);
  v.width = v.height = 10;
  v.region = {0, 0, 11, 10};
  EXPECT_THROW(v.validate(), std::invalid_argument);
  v.region = {2, 2, 5, 5};
  EXPECT_NO_THROW(v.validate());
  EXPECT_EQ(v.cropped({0, 0, 1, 1}).region.width(), 1u);
}

// Cameras are nodes: the Transforms above one move it, on the replica too.
TEST(View, ACameraUnderATransformFollowsIt) {
  sg::Scene s;
  auto& dolly = s.create<sg::Transform>("dolly");
  auto& cam = s.create<sg::Camera>("camera");
  cam.lookAt({0, 0, 5}, {0, 0, 0});
  dolly.addChild(cam.id());
  const auto eyeAt = [](const View& v, glm::vec3 expected) {
    return glm::length(glm::vec3(v.cameraToWorld[3]) - expected) < 1e-5f;
  };
  EXPECT_TRUE(eyeAt(View::fromCamera(cam, 8, 8), {0, 0, 5}));
  sg::Scene replica;
  replica.apply(*s.commit());
  dolly.setMatrix(glm::translate(glm::mat4(1.0f), glm::vec3(2, 0, 0)));
  replica.apply(*s.commit());
  EXPECT_TRUE(eyeAt(View::fromCamera(cam, 8, 8), {2, 0, 5}));
  EXPECT_TRUE(eyeAt(View::fromCamera(*replica.find<sg::Camera>(cam.id()), 8, 8), {2, 0, 5}));
  // A camera held by no node: its pose is its world pose.
  auto& loose = s.create<sg::Camera>();
  loose.lookAt({1, 2, 3}, {0, 0, 0});
  EXPECT_TRUE(eyeAt(View::fromCamera(loose, 8, 8), {1, 2, 3}));
}

// A camera under a moving Transform carries the shutter and its pose at the
// frame interval's end into the view (and each eye of a stereo pair); a
// still one has none, and a shutter it cannot have is an instant.
TEST(View, AMovingCameraCarriesItsShutterAndItsPoseAtTheFramesEnd) {
  sg::Scene s;
  auto& dolly = s.create<sg::Transform>("dolly");
  auto& cam = s.create<sg::Camera>("camera");
  cam.lookAt({0, 0, 5}, {0, 0, 0});
  cam.setShutterOpen(0.25f);
  cam.setShutterClose(0.75f);
  dolly.addChild(cam.id());
  View still = View::fromCamera(cam, 8, 8);
  EXPECT_FALSE(still.cameraToWorldAtEnd.has_value());
  EXPECT_EQ(still.shutterOpen, 0.25f);
  EXPECT_EQ(still.shutterClose, 0.75f);
  dolly.setFrameMotion(glm::translate(glm::mat4(1.0f), glm::vec3(2, 0, 0)));
  const View moving = View::fromCamera(cam, 8, 8);
  ASSERT_TRUE(moving.cameraToWorldAtEnd.has_value());
  EXPECT_LT(glm::length(glm::vec3((*moving.cameraToWorldAtEnd)[3]) - glm::vec3(2, 0, 5)), 1e-5f);
  EXPECT_LT(glm::length(glm::vec3(moving.cameraToWorld[3]) - glm::vec3(0, 0, 5)), 1e-5f) << "now: where it is";
  const View left = moving.eye(med::Eye::Left, 0.2f, 5.0f);
  EXPECT_LT(glm::length(glm::vec3((*left.cameraToWorldAtEnd)[3]) - glm::vec3(1.9f, 0, 5)), 1e-5f);
  EXPECT_NO_THROW(moving.validate());
  cam.setShutterOpen(0.9f);  // opens after it closes
  const View instant = View::fromCamera(cam, 8, 8);
  EXPECT_EQ(instant.shutterOpen, 0.0f);
  EXPECT_EQ(instant.shutterClose, 0.0f);
}
