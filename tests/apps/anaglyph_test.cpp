// tessera-anaglyph: its image is the composition of two eye renders made
// apart (locally and through two nodes), its window presents that image
// and follows the keys and the mouse, and bad input is one error line.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>

#include "../cluster/node_process.hpp"
#include "backends.hpp"
#include "camera_navigation.hpp"
#include "command_runner.hpp"
#include "scene_session.hpp"
#include "tsr/med/compositing.hpp"
#include "tsr/med/image_file.hpp"

namespace tsr::test {
namespace {

using ::testing::HasSubstr;

// 64x48 cornell box, few samples; eyes far apart so the two images differ.
const std::string kRender = " --size 64x48 --spp 2 --max-depth 3 --seed 7 --threads 1";
const float kSeparation = 60, kZeroParallax = 1000;
const std::string kEyes = " --eye-separation 60 --zero-parallax 1000";

// Left and right eye rendered by two separate viewports, composed.
med::FrameBuffer composedLocally(med::AnaglyphMethod method, float separation = kSeparation) {
  app::SceneSession session;
  session.load("builtin:cornell");
  session.publish();
  med::ViewportRegistry registry;
  app::registerBackends(registry);
  med::ContextPool contexts;
  med::ViewportSettings settings;
  settings.backend = "embree";
  settings.root = session.imported.root;
  settings.background = session.imported.background;
  settings.parameters.set("spp", std::int64_t{2});
  settings.parameters.set("maxDepth", std::int64_t{3});
  settings.parameters.set("seed", std::int64_t{7});
  settings.parameters.set("threads", std::int64_t{1});
  const auto view = med::View::fromCamera(*session.replica.scene().find<sg::Camera>(session.camera), 64, 48);
  med::FrameBuffer left, right;
  registry.create(settings, contexts)
      ->render(session.replica, view.eye(med::Eye::Left, separation, kZeroParallax), left);
  med::ContextPool otherContexts;  // the right eye converts the scene anew: nothing shared with the left
  registry.create(settings, otherContexts)
      ->render(session.replica, view.eye(med::Eye::Right, separation, kZeroParallax), right);
  return med::anaglyph(left, right, method);
}

bool sameColour(const med::FrameBuffer& a, const med::FrameBuffer& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.colour.data(), b.colour.data(), a.colour.size() * sizeof(glm::vec4)) == 0;
}

// Largest per-channel difference of two images (same size).
float maxDifference(const med::FrameBuffer& a, const med::FrameBuffer& b) {
  float d = 0;
  for (std::size_t i = 0; i < a.colour.size(); ++i)
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(a.colour[i][c] - b.colour[i][c]));
  return d;
}

class AnaglyphCommand : public CommandTest {
 protected:
  Outcome anaglyph(const std::string& args) { return runBinary(TSR_ANAGLYPH_PATH, args); }
  med::FrameBuffer expected(med::AnaglyphMethod method, float separation = kSeparation) {
    // Through the same file writer, so both sides are rounded alike.
    const auto path = (dir / "expected.exr").string();
    med::writeImage(path, composedLocally(method, separation));
    return med::readImage(path);
  }
};

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

// Under xvfb-run (ctest runs AnaglyphWindow.* that way, see CMakeLists.txt).
class AnaglyphWindow : public AnaglyphCommand {
 protected:
  void SetUp() override {
    AnaglyphCommand::SetUp();
    const char* display = std::getenv("DISPLAY");
    if (!display || !*display) GTEST_SKIP() << "no DISPLAY: ctest runs this under xvfb-run -a";
  }
};

TEST_F(AnaglyphWindow, ShowsTheHeadlessImageAndFollowsKeysAndMouse) {
  std::ofstream(dir / "actions.script") << "frames 2\nscreenshot first.png\n"
                                           "key ]\nframes 1\nscreenshot wider.png\n"
                                           "key m\nframes 1\nscreenshot redcyan.png\n"
                                           "orbit 80 0\nframes 1\nscreenshot orbited.png\n";
  auto r = anaglyph("builtin:cornell" + kRender + kEyes + " --script actions.script");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("eye separation 75, zero parallax 1000, dubois"));
  auto shot = [&](const char* name) { return med::readImage((dir / name).string()); };
  // What the window shows is the headless image, up to 8-bit rounding (the
  // swapchain and the PNG writer each encode sRGB).
  const auto headless = [&](const std::string& args, const char* file) {
    auto h = anaglyph("builtin:cornell" + kRender + args + " --output " + file);
    EXPECT_EQ(h.status, 0) << h.err;
    return med::readImage((dir / file).string());
  };
  EXPECT_LE(maxDifference(shot("first.png"), headless(kEyes, "first-headless.png")), 0.01f);
  // ] widens the eyes by 1.25: the image of --eye-separation 75.
  EXPECT_LE(
      maxDifference(shot("wider.png"), headless(" --eye-separation 75 --zero-parallax 1000", "wider-headless.png")),
      0.01f);
  EXPECT_GT(maxDifference(shot("wider.png"), shot("first.png")), 0.05f);
  EXPECT_LE(maxDifference(shot("redcyan.png"), headless(" --eye-separation 75 --zero-parallax 1000 --method red-cyan",
                                                        "redcyan-headless.png")),
            0.01f);
  // Dragging moves the camera: another view of the box.
  EXPECT_GT(maxDifference(shot("orbited.png"), shot("redcyan.png")), 0.05f);
}

TEST_F(AnaglyphWindow, OnNodesTheCameraMovesTooAsTheLocalWindowShows) {
  // The drag edits the scene camera; the nodes follow through change lists.
  std::ofstream(dir / "orbit.script") << "frames 1\norbit -60 20\nframes 1\nscreenshot orbited.png\n";
  cluster::test::TokenFile token("anaglyph token");
  cluster::test::NodeProcess left({"--token-file", token.path()}), right({"--token-file", token.path()});
  auto r = anaglyph("builtin:cornell" + kRender + kEyes + " --nodes " + left.text() + "," + right.text() +
                    " --token-file " + token.path() + " --script orbit.script");
  ASSERT_EQ(r.status, 0) << r.err;
  std::filesystem::rename(dir / "orbited.png", dir / "nodes-orbited.png");
  r = anaglyph("builtin:cornell" + kRender + kEyes + " --script orbit.script");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto local = med::readImage((dir / "orbited.png").string());
  EXPECT_EQ(maxDifference(med::readImage((dir / "nodes-orbited.png").string()), local), 0.0f);
  auto h = anaglyph("builtin:cornell" + kRender + kEyes + " --output unmoved.png");
  ASSERT_EQ(h.status, 0) << h.err;
  EXPECT_GT(maxDifference(med::readImage((dir / "unmoved.png").string()), local), 0.05f);
}

}  // namespace
}  // namespace tsr::test
