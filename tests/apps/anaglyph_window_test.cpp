// tessera-anaglyph's window: it presents the headless image, follows keys
// and drags, and on nodes the camera edit travels as a change list. Needs
// an X display: ctest runs this binary through `xvfb-run -a` with
// TSR_REQUIRE_DISPLAY=1 (CMakeLists.txt), so a missing display fails there.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "../cluster/node_process.hpp"
#include "anaglyph_fixture.hpp"

namespace tsr::test {
namespace {

using ::testing::HasSubstr;

class AnaglyphWindow : public AnaglyphCommand {
 protected:
  void SetUp() override {
    AnaglyphCommand::SetUp();
    const char* display = std::getenv("DISPLAY");
    const char* required = std::getenv("TSR_REQUIRE_DISPLAY");
    if (display && *display) return;
    if (required && std::string(required) == "1") FAIL() << "no DISPLAY although TSR_REQUIRE_DISPLAY=1";
    GTEST_SKIP() << "no DISPLAY: ctest runs this under xvfb-run -a";
  }
};

TEST_F(AnaglyphWindow, ShowsTheHeadlessImageAndFollowsKeysAndMouse) {
  std::ofstream(dir / "actions.script") << "frames 2\nscreenshot first.png\n"
                                           "key ]\nframes 1\nscreenshot wider.png\n"
                                           "key m\nframes 1\nscreenshot redcyan.png\n"
                                           "orbit 80 0\nframes 1\nscreenshot orbited.png\n";
  // Without the history, each change shows what a fresh render shows (with
  // it, the eyes' samples move with them: another image, measured apart).
  auto r = anaglyph("builtin:cornell" + kRender + kEyes + " --param history=false --script actions.script");
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
