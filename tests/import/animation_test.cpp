#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "import_test_util.hpp"
#include "test_scenes.hpp"
#include "tsr/sg/import/importer.hpp"

namespace tsr::sg {
namespace {

constexpr float kEps = 1e-5f;

// Node 0 "mover" (T 0,0,0 with translation LINEAR, rotation STEP and scale
// CUBICSPLINE channels); node 1 "spinner" (rotation LINEAR); node 2 still.
std::string writeAnimated(const test::TempDir& dir) {
  test::GltfBuilder b = test::tinyScene();
  using nlohmann::json;
  const float s = std::sqrt(0.5f);
  const int t3 = b.addFloats({0, 1, 2}, "SCALAR");
  const int t2 = b.addFloats({0, 1}, "SCALAR");
  const int translation = b.addFloats({0, 0, 0, 2, 0, 0, 2, 4, 0}, "VEC3");
  const int rotation = b.addFloats({0, 0, 0, 1, 0, 0, s, s}, "VEC4");
  // Per key: in-tangent, value, out-tangent.
  const int scale = b.addFloats({0, 0, 0, 1, 1, 1, 2, 2, 2, 0, 0, 0, 3, 3, 3, 0, 0, 0}, "VEC3");
  const int spin = b.addFloats({0, 0, 0, 1, 0, s, 0, s}, "VEC4");
  b.doc["nodes"] = json::array({{{"name", "mover"}, {"mesh", 0}},
                                {{"name", "spinner"}, {"mesh", 0}, {"translation", {0.0, 0.0, 5.0}}},
                                {{"name", "still"}, {"mesh", 0}}});
  b.doc["scenes"] = {{{"nodes", {0, 1, 2}}}};
  b.doc["animations"] = {{{"name", "clip"},
                          {"samplers",
                           {{{"input", t3}, {"output", translation}},
                            {{"input", t2}, {"output", rotation}, {"interpolation", "STEP"}},
                            {{"input", t2}, {"output", scale}, {"interpolation", "CUBICSPLINE"}},
                            {{"input", t2}, {"output", spin}, {"interpolation", "LINEAR"}}}},
                          {"channels",
                           {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}},
                            {{"sampler", 1}, {"target", {{"node", 0}, {"path", "rotation"}}}},
                            {{"sampler", 2}, {"target", {{"node", 0}, {"path", "scale"}}}},
                            {{"sampler", 3}, {"target", {{"node", 1}, {"path", "rotation"}}}}}}}};
  std::string path = dir.file("animated.gltf");
  b.writeGltf(path);
  return path;
}

class GltfAnimation : public ::testing::Test {
 protected:
  void SetUp() override {
    result = importScene(scene, writeAnimated(dir));
    ASSERT_EQ(result.animations.size(), 1u);
    mover = test::byName<Transform>(scene, "mover");
    spinner = test::byName<Transform>(scene, "spinner");
    ASSERT_TRUE(mover && spinner);
  }
  const Animation& anim() const { return result.animations[0]; }
  test::TempDir dir;
  Scene scene;
  ImportResult result;
  Transform* mover = nullptr;
  Transform* spinner = nullptr;
};

TEST_F(GltfAnimation, SamplesEachInterpolation) {
  EXPECT_FLOAT_EQ(anim().duration(), 2.0f);
  EXPECT_EQ(anim().channels().size(), 4u);
  const auto at = [&](float t) { return anim().poseAt(mover->id(), t); };
  // LINEAR translation.
  EXPECT_NEAR(glm::distance(at(0.5f).translation, Vec3(1, 0, 0)), 0.0f, kEps);
  EXPECT_NEAR(glm::distance(at(1.5f).translation, Vec3(2, 2, 0)), 0.0f, kEps);
  // STEP rotation holds the earlier key until the next one.
  EXPECT_NEAR(at(0.99f).rotation.w, 1.0f, kEps);
  EXPECT_NEAR(at(1.0f).rotation.z, std::sqrt(0.5f), kEps);
  // CUBICSPLINE: p0=1, m0=2, p1=3, m1=0 at s=0.5 gives 2.25.
  EXPECT_NEAR(at(0.5f).scale.x, 2.25f, kEps);
  EXPECT_NEAR(at(1.0f).scale.y, 3.0f, kEps);
  // Times clamp at both ends.
  EXPECT_NEAR(glm::distance(at(-3.0f).translation, Vec3(0)), 0.0f, kEps);
  EXPECT_NEAR(glm::distance(at(9.0f).translation, Vec3(2, 4, 0)), 0.0f, kEps);
  EXPECT_NEAR(at(9.0f).scale.z, 3.0f, kEps);
}

TEST_F(GltfAnimation, SlerpsRotationsAndKeepsTheRestPose) {
  const Animation::Pose half = anim().poseAt(spinner->id(), 0.5f);
  const glm::quat expected = glm::angleAxis(glm::quarter_pi<float>(), Vec3(0, 1, 0));
  EXPECT_NEAR(std::abs(glm::dot(half.rotation, expected)), 1.0f, kEps);
  EXPECT_NEAR(glm::distance(half.translation, Vec3(0, 0, 5)), 0.0f, kEps);  // not animated: rest pose
}

TEST_F(GltfAnimation, ApplyChangesExactlyTheAnimatedMatrices) {
  scene.commit();
  EXPECT_EQ(anim().apply(scene, 0.5f), 2u);
  const ChangeListPtr changes = scene.commit();
  EXPECT_TRUE(changes->creations().empty());
  EXPECT_TRUE(changes->destructions().empty());
  ASSERT_EQ(changes->changes().size(), 2u);
  std::vector<ContainerId> touched;
  for (const ChangeEntry& e : changes->changes()) {
    EXPECT_EQ(e.mask, fieldBit(Transform::Matrix));
    touched.push_back(e.id);
  }
  std::sort(touched.begin(), touched.end());
  std::vector<ContainerId> expected{mover->id(), spinner->id()};
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(touched, expected);
  EXPECT_NEAR(glm::distance(Vec3(mover->matrix()[3]), Vec3(1, 0, 0)), 0.0f, kEps);
  EXPECT_NEAR(glm::distance(Vec3(spinner->matrix()[3]), Vec3(0, 0, 5)), 0.0f, kEps);
}

// With a frame interval, apply also writes each target's motion over it
// (for a shutter to blur): at the interval's end the matrix is the pose
// then. Without one, a still motion is left unedited.
TEST_F(GltfAnimation, ApplyWithAFrameIntervalWritesTheMotionOverIt) {
  scene.commit();
  anim().apply(scene, 0.5f, 0.25f);
  const ChangeListPtr changes = scene.commit();
  for (const ChangeEntry& e : changes->changes())
    EXPECT_EQ(e.mask, fieldBit(Transform::Matrix) | fieldBit(Transform::FrameMotion));
  for (const Transform* t : {mover, spinner}) {
    const Mat4 expected = anim().poseAt(t->id(), 0.75f).matrix();
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) EXPECT_NEAR(t->matrixAtEnd()[c][r], expected[c][r], 1e-5f) << t->name();
  }
  anim().apply(scene, 0.5f);  // no interval: still again
  EXPECT_EQ(mover->frameMotion(), Mat4(1.0f));
  scene.commit();
  anim().apply(scene, 0.5f);
  for (const ChangeEntry& e : scene.commit()->changes()) EXPECT_EQ(e.mask, fieldBit(Transform::Matrix));
}

TEST(Animation, RejectsBadKeys) {
  Animation a;
  EXPECT_THROW(
      a.addChannel({1, Animation::Path::Translation, Animation::Interpolation::Linear, {1, 0}, {Vec4(0), Vec4(0)}}),
      std::invalid_argument);
  EXPECT_THROW(
      a.addChannel({1, Animation::Path::Scale, Animation::Interpolation::CubicSpline, {0, 1}, {Vec4(0), Vec4(0)}}),
      std::invalid_argument);
  EXPECT_THROW(a.addChannel({1, Animation::Path::Scale, Animation::Interpolation::Step, {0}, {Vec4(NAN)}}),
               std::invalid_argument);
  EXPECT_TRUE(a.channels().empty());
}

TEST(Animation, LoopingWrapsTime) {
  Animation a;
  a.setLooping(true);
  a.addChannel(
      {7, Animation::Path::Translation, Animation::Interpolation::Linear, {0, 4}, {Vec4(0), Vec4(4, 0, 0, 0)}});
  EXPECT_NEAR(a.poseAt(7, 5.0f).translation.x, 1.0f, kEps);
  EXPECT_NEAR(a.poseAt(7, -1.0f).translation.x, 3.0f, kEps);
  a.setLooping(false);
  EXPECT_NEAR(a.poseAt(7, 5.0f).translation.x, 4.0f, kEps);
}

}  // namespace
}  // namespace tsr::sg
