// tessera-anaglyph: its image is the composition of two eye renders made
// apart (locally and through two nodes), and bad input is one error line.
// The window's tests are in anaglyph_window_test.cpp (under xvfb-run).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>

#include "../cluster/node_process.hpp"
#include "anaglyph_fixture.hpp"
#include "camera_navigation.hpp"

namespace tsr::test {
namespace {

using ::testing::HasSubstr;

TEST_F(AnaglyphCommand, OutputEqualsTheCompositionOfTwoLocalEyeRenders) {
  for (auto [name, method] :
       {std::pair{"dubois", med::AnaglyphMethod::Dubois}, std::pair{"red-cyan", med::AnaglyphMethod::RedCyan}}) {
    auto r = anaglyph("builtin:cornell" + kRender + kEyes + " --method " + name + " --output " + name + ".exr");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_THAT(r.out, HasSubstr("wrote " + std::string(name) + ".exr"));
    EXPECT_TRUE(sameColour(med::readImage((dir / (std::string(name) + ".exr")).string()), expected(method))) << name;
  }
  // The eyes differ: an image with the eyes together is another image.
  auto r = anaglyph("builtin:cornell" + kRender + " --eye-separation 0 --zero-parallax 1000 --output mono.exr");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_GT(maxDifference(med::readImage((dir / "mono.exr").string()), expected(med::AnaglyphMethod::Dubois)), 0.05f);
}

TEST_F(AnaglyphCommand, TwoNodesRenderTheEyesOfTheLocalImage) {
  cluster::test::TokenFile token("anaglyph token");
  cluster::test::NodeProcess left({"--token-file", token.path()}), right({"--token-file", token.path()});
  auto r = anaglyph("builtin:cornell" + kRender + kEyes + " --nodes " + left.text() + "," + right.text() +
                    " --token-file " + token.path() + " --output nodes.exr");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(sameColour(med::readImage((dir / "nodes.exr").string()), expected(med::AnaglyphMethod::Dubois)));
  // One node renders both eyes (its two viewports share one converted scene).
  r = anaglyph("builtin:cornell" + kRender + kEyes + " --nodes " + left.text() + " --token-file " + token.path() +
               " --output one-node.exr");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(sameColour(med::readImage((dir / "one-node.exr").string()), expected(med::AnaglyphMethod::Dubois)));
}

// Without --zero-parallax the screen plane goes through the centre of the
// scene's bounds, seen from the camera where it sits in the world: about
// 1080 mm in front of builtin:cornell's camera (at z = -800, the box's
// centre at z = 280), with the eyes 1/30 of that apart.
TEST_F(AnaglyphCommand, TheDefaultScreenPlaneGoesThroughTheSceneCentre) {
  auto r = anaglyph("builtin:cornell" + kRender + " --output default.png");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto at = r.out.find("zero parallax ");
  ASSERT_NE(at, std::string::npos) << r.out;
  const float zeroParallax = std::stof(r.out.substr(at + 14));
  EXPECT_NEAR(zeroParallax, 1080.0f, 10.0f) << r.out;
  EXPECT_THAT(r.out, HasSubstr("eye separation " + std::to_string(int(zeroParallax / 30.0f))));
}

TEST_F(AnaglyphCommand, BadInputIsOneErrorLine) {
  expectOneErrorLine(anaglyph("builtin:cornell --method blue --output x.png"), "--method");
  expectOneErrorLine(anaglyph("builtin:cornell --nodes 127.0.0.1:1,127.0.0.1:2,127.0.0.1:3 --output x.png"),
                     "1 or 2 nodes");
  expectOneErrorLine(anaglyph("builtin:cornell --token-file t --output x.png"), "--token-file needs --nodes");
  expectOneErrorLine(anaglyph("builtin:cornell --zero-parallax 0 --output x.png"), "--zero-parallax");
  std::ofstream(dir / "bad.script") << "frames 1\nkey x\n";
  expectOneErrorLine(anaglyph("builtin:cornell --script bad.script"), "bad.script line 2: key needs one of");
  std::ofstream(dir / "bad2.script") << "# comment\norbit 10\n";
  expectOneErrorLine(anaglyph("builtin:cornell --script bad2.script"), "line 2: orbit needs a number");
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

TEST(CameraNavigation, OrbitsAboutTheTargetAndDolliesTowardsIt) {
  const glm::mat4 pose = glm::inverse(glm::lookAt(glm::vec3(0, 0, 10), glm::vec3(0), glm::vec3(0, 1, 0)));
  app::CameraNavigation nav(pose, 10);
  EXPECT_NEAR(glm::length(nav.target()), 0, 1e-5f);
  nav.orbit(90, 0);  // a quarter turn about +Y: from +Z to +X
  EXPECT_NEAR(nav.eye().x, 10, 1e-4f);
  EXPECT_NEAR(nav.eye().z, 0, 1e-4f);
  glm::vec3 forward = -glm::vec3(nav.pose()[2]);
  EXPECT_NEAR(glm::dot(forward, glm::vec3(-1, 0, 0)), 1, 1e-5f);  // still looking at the target
  nav.orbit(270, 0);
  EXPECT_NEAR(glm::distance(nav.eye(), glm::vec3(0, 0, 10)), 0, 1e-3f);
  nav.orbit(0, 500);  // pitch stops short of the pole
  EXPECT_LT(nav.eye().y, 10.0f);
  EXPECT_GT(nav.eye().y, 9.9f);
  app::CameraNavigation near(pose, 10);
  near.dolly(1);
  EXPECT_NEAR(near.eye().z, 9, 1e-4f);
  near.pan(0.1f, 0);  // both move: the view direction stays
  EXPECT_NEAR(near.eye().x, 0.9f, 1e-4f);
  EXPECT_NEAR(near.target().x, 0.9f, 1e-4f);
}

}  // namespace
}  // namespace tsr::test
