// The camera every back-end uses: one set of rules for what is refused.
#include "tsr/backend/camera.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <limits>

namespace tsr::backend {
namespace {

using ::testing::HasSubstr;

std::string reason(const Camera& c) { return c.invalidReason().value_or(""); }

TEST(BackendCamera, LookAtPutsTheWindowOnTheNearPlane) {
  const Camera c = Camera::lookAt({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 1.0f, 2.0f, 0.5f, 50.0f);
  EXPECT_FALSE(c.invalidReason());
  EXPECT_FLOAT_EQ(c.top, 0.5f * std::tan(0.5f));
  EXPECT_FLOAT_EQ(c.right, 2.0f * c.top);
  EXPECT_EQ(c.near, 0.5f);
  EXPECT_EQ(c.far, 50.0f);
  EXPECT_LT(glm::length(glm::vec3(c.worldToCamera() * glm::vec4(0, 0, 5, 1))), 1e-5f) << "the eye is the origin";
}

TEST(BackendCamera, EachRuleIsNamed) {
  const Camera good;
  EXPECT_FALSE(good.invalidReason());
  Camera c = good;
  c.cameraToWorld[0][0] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THAT(reason(c), HasSubstr("NaN"));
  c = good;
  c.cameraToWorld[3][2] = 2e12f;
  EXPECT_THAT(reason(c), HasSubstr("the eye cannot be traced"));
  c = good;
  c.cameraToWorld[0][0] = 0.0f;
  EXPECT_THAT(reason(c), HasSubstr("singular"));
  c = good;
  c.right = c.left;
  EXPECT_THAT(reason(c), HasSubstr("window is empty"));
  c = good;
  c.near = 0.0f;
  EXPECT_THAT(reason(c), HasSubstr("near must be positive"));
  c = good;
  c.far = c.near;
  EXPECT_THAT(reason(c), HasSubstr("far must be greater than near"));
  c = good;
  c.far = std::numeric_limits<float>::infinity();
  EXPECT_THAT(reason(c), HasSubstr("far must be finite"));
  c = good;
  c.apertureRadius = -1.0f;
  EXPECT_THAT(reason(c), HasSubstr("aperture"));
  c = good;
  c.focusDistance = 0.0f;
  EXPECT_THAT(reason(c), HasSubstr("focus distance"));
  c = good;
  c.shutterOpen = 0.6f;
  c.shutterClose = 0.5f;
  EXPECT_THAT(reason(c), HasSubstr("shutter"));
  c = good;
  c.cameraToWorldAtEnd = glm::mat4(0.0f);
  EXPECT_THAT(reason(c), HasSubstr("at the frame's end is singular"));
}

TEST(BackendCamera, FarMayLieBeyondTheCoordinateLimit) {
  Camera c;
  c.far = 1e30f;  // glTF's "infinite" far plane
  EXPECT_FALSE(c.invalidReason());
}

}  // namespace
}  // namespace tsr::backend
