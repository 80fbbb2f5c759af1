// tessera-viewer in a real window: ctest runs this binary through
// `xvfb-run -a` with TSR_REQUIRE_DISPLAY=1 (tests/apps/CMakeLists.txt), so a
// broken Xvfb fails rather than skips. Scripted runs switch back-ends, take
// screenshots and are compared with headless tessera-render images of the
// same view.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <glm/trigonometric.hpp>
#include <glm/vec3.hpp>

#include "../cluster/node_process.hpp"
#include "command_runner.hpp"
#include "tsr/imageio/image_codec.hpp"
#include "tsr/med/image_file.hpp"

namespace {

using ::testing::HasSubstr;
using tsr::test::Outcome;

// Per-channel differences of two 8-bit images read back as linear floats,
// measured on the sRGB-encoded values (0..1) people see.
struct Difference {
  double meanAbs = 0;  // mean |a - b| over channels and pixels
  double maxAbs = 0;
};

float encode(float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

Difference compare(const tsr::med::FrameBuffer& a, const tsr::med::FrameBuffer& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  Difference d;
  if (a.colour.size() != b.colour.size()) {
    d.meanAbs = d.maxAbs = 1;
    return d;
  }
  for (std::size_t i = 0; i < a.colour.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double e = std::abs(encode(a.colour[i][c]) - encode(b.colour[i][c]));
      d.meanAbs += e;
      d.maxAbs = std::max(d.maxAbs, e);
    }
  d.meanAbs /= double(a.colour.size() * 3);
  return d;
}

// Fraction of pixels that are not black, and the spread of their values.
double litFraction(const tsr::med::FrameBuffer& fb) {
  std::size_t lit = 0;
  for (const auto& p : fb.colour)
    if (p.r + p.g + p.b > 0.01f) ++lit;
  return double(lit) / double(fb.colour.size());
}

bool displayRequired() {
  const char* v = std::getenv("TSR_REQUIRE_DISPLAY");
  return v && *v && std::string(v) != "0";
}

class ViewerWindow : public tsr::test::CommandTest {
 protected:
  void SetUp() override {
    CommandTest::SetUp();
    const char* display = std::getenv("DISPLAY");
    if (!display || !*display) {
      if (displayRequired()) FAIL() << "no DISPLAY (run through xvfb-run -a)";
      GTEST_SKIP() << "no DISPLAY (run through xvfb-run -a)";
    }
  }
  Outcome viewer(const std::string& args) { return runBinary(TSR_VIEWER_PATH, args); }
  Outcome render(const std::string& args) { return runBinary(TSR_RENDER_PATH, args); }
  void writeScript(const std::string& name, const std::string& text) { std::ofstream(dir / name) << text; }
  tsr::med::FrameBuffer image(const std::string& name) { return tsr::med::readImage((dir / name).string()); }
};

// Tolerances (sRGB-encoded values, 0..1): the rasteriser and the coverage
// renderer are deterministic, so a viewport matches tessera-render's image
// of the same view to 1/255 in every pixel; the path tracer seeds samples
// by index, so 8 samples taken one a frame match an 8-spp batch render to
// a mean of 0.5/255 (and 4/255 in any pixel: float sums in another order).
TEST_F(ViewerWindow, ScriptedBackendSwitchesMatchHeadlessRenders) {
  writeScript("switch.txt", "# every back-end in turn, one viewport of 160x120; animations held at 0 s\n"
                            "time 0\n"
                            "backend 0 vulkan\n"
                            "wait frames 2\n"
                            "screenshot vulkan.png\n"
                            "backend 0 coverage\n"
                            "wait frames 2\n"
                            "screenshot coverage.png\n"
                            "backend 0 embree\n"
                            "wait samples 8\n"
                            "screenshot embree.png\n"
                            "backend 0 vulkan\n"
                            "wait frames 2\n"
                            "screenshot vulkan-again.png\n"
                            "window-screenshot window.png\n");
  const Outcome v = viewer("builtin:animated --size 160x120 --spp 8 --max-depth 4 --script switch.txt --exit-after");
  ASSERT_EQ(v.status, 0) << v.err;
  // Each back-end converts the scene once; going back to the rasteriser syncs its kept viewport.
  EXPECT_THAT(v.out, HasSubstr("viewport 0: vulkan, scene converted"));
  EXPECT_THAT(v.out, HasSubstr("viewport 0: coverage, scene converted"));
  EXPECT_THAT(v.out, HasSubstr("viewport 0: embree, scene converted"));
  EXPECT_THAT(v.out, HasSubstr("path tracer preview filter: pixel")) << "the viewer opens filtered";
  std::size_t conversions = 0;
  for (auto at = v.out.find("vulkan, scene converted"); at != std::string::npos;
       at = v.out.find("vulkan, scene converted", at + 1))
    ++conversions;
  EXPECT_EQ(conversions, 1u) << v.out;

  for (const char* backend : {"vulkan", "coverage", "embree"}) {
    // The path tracer's preview is filtered unless asked otherwise.
    // --spp and --max-depth are the path tracer's: the others refuse them.
    const std::string pathTracer = std::string(backend) == "embree" ? " --filter pixel --spp 8 --max-depth 4" : "";
    const Outcome r = render(std::string("builtin:animated --size 160x120 --quiet --backend ") + backend + pathTracer +
                             " --output ref-" + backend + ".png");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto shot = image(std::string(backend) + ".png");
    const auto ref = image(std::string("ref-") + backend + ".png");
    ASSERT_EQ(shot.width, 160u);
    ASSERT_EQ(shot.height, 120u);
    EXPECT_GT(litFraction(shot), 0.3) << backend << ": not blank";
    const Difference d = compare(shot, ref);
    if (std::string(backend) == "embree") {
      EXPECT_LE(d.meanAbs, 0.5 / 255) << backend;
      EXPECT_LE(d.maxAbs, 4.0 / 255) << backend;
    } else {
      EXPECT_LE(d.maxAbs, 1.0 / 255 + 1e-6) << backend;
    }
  }
  // The back-ends show different pictures of the room.
  EXPECT_GT(compare(image("vulkan.png"), image("coverage.png")).meanAbs, 0.05);
  EXPECT_GT(compare(image("vulkan.png"), image("embree.png")).meanAbs, 0.02);
  EXPECT_GT(compare(image("embree.png"), image("coverage.png")).meanAbs, 0.05);
  // Back to the rasteriser: the same picture as before.
  EXPECT_LE(compare(image("vulkan.png"), image("vulkan-again.png")).maxAbs, 1.0 / 255 + 1e-6);
  // The window holds the viewport and the panels drawn over it.
  const auto window = image("window.png");
  EXPECT_EQ(window.width, 160u);
  EXPECT_GT(compare(window, image("vulkan-again.png")).meanAbs, 0.01) << "panels drawn over the image";
}

double meanLinear(const tsr::med::FrameBuffer& fb) {
  double sum = 0;
  for (const auto& p : fb.colour) sum += double(p.r) + p.g + p.b;
  return sum / (3.0 * double(fb.colour.size()));
}

// Issue 46: switching a viewport from the path tracer to the rasteriser
// keeps the look. glTF's default material (white metal, roughness 1) under
// the default light rig was 41 % darker in the rasteriser; the two
// screenshots' mean brightness now agrees within 10 %. The quad faces the
// camera, so its depths have no extent: the viewer's pixel filter used to
// refuse such a frame (sigmaD below its least), and the viewer exited.
TEST_F(ViewerWindow, SwitchingFromThePathTracerToTheRasteriserKeepsTheBrightness) {
  const std::string quad =
      "/usr/share/assimp/models/glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_04.gltf";
  ASSERT_TRUE(std::filesystem::exists(quad)) << "scripts/install-deps.sh installs assimp-testmodels";
  writeScript("look.txt", "backend 0 embree\nwait samples 16\nscreenshot traced.png\n"
                          "backend 0 vulkan\nwait frames 2\nscreenshot raster.png\n");
  const Outcome v = viewer("'" + quad + "' --size 96x96 --script look.txt --exit-after");
  ASSERT_EQ(v.status, 0) << v.err;
  const double traced = meanLinear(image("traced.png")), raster = meanLinear(image("raster.png"));
  EXPECT_GT(traced, 0.3) << "the quad is lit";
  EXPECT_NEAR(raster / traced, 1.0, 0.10) << "raster " << raster << ", path tracer " << traced;
}

// The panels leave the picture to the user: at the default size, with two
// viewports side by side (as issue 43 saw them covering most of both
// pictures), they open collapsed and cover little of either picture, and
// the viewer opens with the path tracer's history on.
TEST_F(ViewerWindow, PanelsOpenCollapsedAndCoverLittleOfThePictures) {
  writeScript("panels.txt", "time 0\nwait frames 2\nscreenshot left.png 0\nscreenshot right.png 1\n"
                            "window-screenshot window.png\n");
  const Outcome v = viewer("builtin:cornell --viewports vulkan,vulkan --script panels.txt --exit-after");
  ASSERT_EQ(v.status, 0) << v.err;
  EXPECT_THAT(v.out, HasSubstr("history while moving: on"));
  const auto window = image("window.png"), left = image("left.png"), right = image("right.png");
  ASSERT_EQ(left.width + right.width, window.width);
  for (const auto* pane : {&left, &right}) {
    const std::uint32_t x0 = pane == &left ? 0 : left.width;
    std::size_t covered = 0;
    for (std::uint32_t y = 0; y < pane->height; ++y)
      for (std::uint32_t x = 0; x < pane->width; ++x) {
        const glm::vec4 a = window.colour[window.index(x0 + x, y)], b = pane->colour[pane->index(x, y)];
        covered += std::abs(encode(a.r) - encode(b.r)) + std::abs(encode(a.g) - encode(b.g)) +
                       std::abs(encode(a.b) - encode(b.b)) >
                   3.0 / 255;
      }
    const double share = double(covered) / double(pane->colour.size());
    EXPECT_GT(share, 0.005) << "the panels' title bars are drawn";
    EXPECT_LT(share, 0.05) << "a collapsed panel covers little of its picture";
  }
}

TEST_F(ViewerWindow, SideBySideViewportsOrbitBookmarksAndLayeredExr) {
  writeScript("orbit.txt", "time 0\n"
                           "wait frames 2\n"
                           "screenshot left.png 0\n"
                           "orbit 40\n"
                           "tilt 10\n"
                           "wait frames 2\n"
                           "screenshot left-orbit.png 0\n"
                           "screenshot right.exr 1\n"
                           "bookmark save side\n");
  const Outcome v = viewer("builtin:animated --viewports vulkan,embree --size 200x100 --spp 2 --max-depth 2 "
                           "--script orbit.txt --exit-after");
  ASSERT_EQ(v.status, 0) << v.err;
  const auto left = image("left.png"), turned = image("left-orbit.png");
  EXPECT_EQ(left.width, 100u) << "two viewports share the window's width";
  EXPECT_EQ(left.height, 100u);
  EXPECT_GT(compare(left, turned).meanAbs, 0.03) << "orbiting changed the view";

  // The path tracer's screenshot as EXR carries its outputs as layers.
  const tsr::imageio::Image exr = tsr::imageio::readFile((dir / "right.exr").string(), tsr::imageio::Sample::Float);
  const auto& names = exr.channelNames;
  for (const char* channel : {"R", "G", "B", "A", "Z", "albedo.R", "normal.G", "direct.B", "indirect.R"})
    EXPECT_NE(std::find(names.begin(), names.end(), channel), names.end()) << channel;
  EXPECT_EQ(exr.width, 100u);

  // The bookmark lies beside the scene (builtin scenes: the current folder)
  // and brings the view back in a new run.
  ASSERT_TRUE(std::filesystem::exists(dir / "builtin-animated.bookmarks.json"));
  writeScript("back.txt", "time 0\nbookmark load side\nwait frames 2\nscreenshot back.png 0\n");
  const Outcome again = viewer("builtin:animated --viewports vulkan --size 100x100 --script back.txt --exit-after");
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_LE(compare(image("back.png"), turned).maxAbs, 1.0 / 255 + 1e-6);
}

// Orbiting turns about the scene's centre in the world, also for a camera
// that hangs under a node (builtin:cornell's, as every glTF camera): the
// view after "orbit 30" is tessera-render's from the eye turned 30 degrees
// about the centre's point on the view axis (278, 273, 279.6), 1079.6 mm away.
TEST_F(ViewerWindow, OrbitTurnsAboutTheSceneCentre) {
  writeScript("turn.txt", "orbit 30\nwait frames 2\nscreenshot turned.png\n");
  const Outcome v = viewer("builtin:cornell --viewports vulkan --size 160x120 --script turn.txt --exit-after");
  ASSERT_EQ(v.status, 0) << v.err;
  const double yaw = glm::radians(210.0), along = 1079.6;  // from behind (+z view): yaw 180, then 30 more
  const glm::dvec3 target(278, 273, 279.6), eye = target + along * glm::dvec3(std::sin(yaw), 0, std::cos(yaw));
  char look[160];
  std::snprintf(look, sizeof look, " --look-from %.3f,%.3f,%.3f --look-at %.3f,%.3f,%.3f", eye.x, eye.y, eye.z,
                target.x, target.y, target.z);
  const Outcome r =
      render(std::string("builtin:cornell --backend vulkan --size 160x120 --quiet --output expected.png") + look);
  ASSERT_EQ(r.status, 0) << r.err;
  const Difference d = compare(image("turned.png"), image("expected.png"));
  EXPECT_LE(d.meanAbs, 0.5 / 255) << "mean";
  EXPECT_GT(litFraction(image("turned.png")), 0.3);
}

// A bookmarks file that does not parse (a typo by hand) is kept: saving a
// bookmark would otherwise replace every bookmark in it with the new one.
TEST_F(ViewerWindow, ABrokenBookmarksFileIsNotSavedOver) {
  const std::string broken = R"({"version": 1, "bookmarks": [{"name": "door", "target": [0, 1, 0],)";
  std::ofstream(dir / "builtin-cornell.bookmarks.json") << broken;
  writeScript("save.txt", "wait frames 1\nbookmark save here\n");
  const Outcome v = viewer("builtin:cornell --viewports coverage --size 64x64 --script save.txt --exit-after");
  EXPECT_EQ(v.status, 2);
  EXPECT_THAT(v.err,
              HasSubstr("error: save.txt:2: not saving over builtin-cornell.bookmarks.json, which could not be read"));
  EXPECT_EQ(slurp(dir / "builtin-cornell.bookmarks.json"), broken);
}

TEST_F(ViewerWindow, CoveragePickSelectsTheObjectUnderThePixel) {
  writeScript("pick.txt", "wait frames 2\nwindow-screenshot before.png\npick 0 80 100\nwait frames 2\n"
                          "window-screenshot picked.png\npick 0 0 0\nwait frames 2\nwindow-screenshot after.png\n");
  const Outcome v =
      viewer("builtin:cornell --viewports coverage --size 160x120 --hide-panels --script pick.txt --exit-after");
  ASSERT_EQ(v.status, 0) << v.err;
  EXPECT_THAT(v.out, HasSubstr("viewport 0: picked object "));
  EXPECT_THAT(v.out, HasSubstr("viewport 0: picked nothing"));
  // The selected object stands out: the window's picture changes, and
  // goes back once the background is clicked.
  EXPECT_GT(compare(image("before.png"), image("picked.png")).meanAbs, 0.05);
  EXPECT_LE(compare(image("before.png"), image("after.png")).maxAbs, 1.0 / 255 + 1e-6);
}

// The lens from a script (as the panel's sliders set it): focus on what a
// pixel of the path-traced viewport shows, open the aperture, and the
// picture blurs away from that depth.
TEST_F(ViewerWindow, LensFocusesOnAPixelAndBlurs) {
  writeScript("lens.txt", "wait samples 4\nscreenshot pinhole.png 0\nlens 40 500\nfocus-on 0 48 60\n"
                          "wait samples 4\nscreenshot lens.png 0\nfocus-on 0 0 0\n");
  const Outcome v = viewer("builtin:cornell --viewports embree --size 96x96 --spp 4 --script lens.txt --exit-after");
  ASSERT_EQ(v.status, 0) << v.err;
  EXPECT_THAT(v.out, HasSubstr("viewport 0: focus distance "));
  EXPECT_GT(compare(image("pinhole.png"), image("lens.png")).meanAbs, 0.01) << "the back of the box blurs";
}

// The shutter from a script (as the panel's sliders set it): with the
// animation paused, opening the shutter over the frame blurs what moves;
// closing it again brings the same picture back.
TEST_F(ViewerWindow, ShutterBlursTheAnimation) {
  writeScript("shutter.txt", "time 1\nwait samples 4\nscreenshot still.png 0\nshutter 0 1\nwait samples 4\n"
                             "screenshot blurred.png 0\nshutter 0 0\nwait samples 4\nscreenshot again.png 0\n");
  const Outcome v =
      viewer("builtin:animated --viewports embree --size 96x96 --spp 4 --script shutter.txt --exit-after");
  ASSERT_EQ(v.status, 0) << v.err;
  // The path tracer draws the same numbers with and without a shutter
  // (sampler.hpp), so the two differ by the blur alone: without it they
  // would be equal.
  EXPECT_GT(compare(image("still.png"), image("blurred.png")).meanAbs, 0.001) << "what moves blurs";
  EXPECT_LE(compare(image("still.png"), image("again.png")).maxAbs, 1e-6) << "an instant again";
}

// Figure 5.6's option: while the camera moves the path-traced viewport
// shows the rasteriser's picture, and path traces once it rests.
TEST_F(ViewerWindow, RasterisesWhileMovingThenPathTraces) {
  writeScript("move.txt", "time 0\nraster-while-moving on\nwait frames 2\norbit 10\n"
                          "screenshot moving.png 0\nscreenshot raster.png 1\n"
                          "wait samples 2\nscreenshot resting.png 0\n");
  const Outcome v = viewer("builtin:animated --viewports embree,vulkan --size 192x72 --spp 2 --max-depth 2 "
                           "--script move.txt --exit-after");
  ASSERT_EQ(v.status, 0) << v.err;
  EXPECT_LE(compare(image("moving.png"), image("raster.png")).maxAbs, 1.0 / 255 + 1e-6) << "rasterised while moving";
  EXPECT_GT(compare(image("resting.png"), image("raster.png")).meanAbs, 0.02) << "path traced at rest";
}

// Figure 5.6's whole chain: the rasteriser while the camera moves, one
// Whitted image (mode=whitted) the moment it rests, shown until the path
// tracer has 2 samples of its own (its first filtered preview), then the
// path tracer.
TEST_F(ViewerWindow, RasterWhileMovingThenWhittedThenPathTracer) {
  writeScript("chain.txt", "raster-while-moving on\nwait frames 2\norbit 10\nreport\nwait samples 1\nreport\n"
                           "screenshot whitted.png\nwait samples 2\nreport\nscreenshot traced.png\n");
  const Outcome v = viewer("builtin:cornell --viewports embree --size 96x72 --spp 8 --script chain.txt --exit-after");
  ASSERT_EQ(v.status, 0) << v.err;
  const auto moving = v.out.find("showing vulkan");
  const auto whitted = v.out.find("showing embree (whitted), 1 samples");
  const auto traced = v.out.find("showing embree, ");  // no "(whitted)": the path tracer's preview is shown
  ASSERT_NE(moving, std::string::npos) << v.out;
  ASSERT_NE(whitted, std::string::npos) << v.out;
  ASSERT_NE(traced, std::string::npos) << v.out;
  EXPECT_LT(moving, whitted);
  EXPECT_LT(whitted, traced);
  EXPECT_GT(compare(image("whitted.png"), image("traced.png")).meanAbs, 0.01) << "two renderers, two pictures";
}

// The time action (the panel's slider) poses the animation; open replaces the scene.
TEST_F(ViewerWindow, AnimationTimeAndOpeningAnotherScene) {
  writeScript("time.txt", "time 0\nwait frames 2\nscreenshot t0.png\ntime 1.5\nwait frames 2\nscreenshot t15.png\n"
                          "open builtin:cornell\nwait frames 2\nscreenshot cornell.png\n");
  const Outcome v = viewer("builtin:animated --viewports coverage --size 96x72 --script time.txt --exit-after");
  ASSERT_EQ(v.status, 0) << v.err;
  const Difference moved = compare(image("t0.png"), image("t15.png"));
  EXPECT_GT(moved.maxAbs, 0.2) << "something moved";
  EXPECT_GT(moved.meanAbs, 0.001) << "something moved";
  const Outcome r = render("builtin:cornell --backend coverage --size 96x72 --quiet --output cornell-ref.png");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_LE(compare(image("cornell.png"), image("cornell-ref.png")).maxAbs, 1.0 / 255 + 1e-6);
}

// A back-end left alone while the camera moved for more frames than the
// replica's change log holds (256) still catches up by syncing: the viewer
// keeps the viewports it does not show within the log.
TEST_F(ViewerWindow, ABackendSwitchedBackAfterLongNavigationSyncs) {
  std::string script = "backend 0 vulkan\nwait frames 1\nbackend 0 coverage\n";
  for (int i = 0; i < 300; ++i) script += "orbit 1\n";
  script += "backend 0 vulkan\nwait frames 1\n";
  writeScript("long.txt", script);
  const Outcome v =
      viewer("builtin:animated --viewports embree --size 48x32 --hide-panels --script long.txt --exit-after");
  ASSERT_EQ(v.status, 0) << v.err;
  const auto back = v.out.rfind("viewport 0: vulkan, scene ");
  ASSERT_NE(back, std::string::npos) << v.out;
  EXPECT_EQ(v.out.compare(back, 33, "viewport 0: vulkan, scene synced "), 0) << v.out;
}

// Keys, typed by xdotool (X's XTEST) into the window: B cycles the back-end
// of the viewport under the mouse, F12 writes every viewport's image, Esc
// quits cleanly.
TEST_F(ViewerWindow, KeysCycleTheBackendScreenshotAndQuit) {
#ifndef TSR_XDOTOOL
  GTEST_SKIP() << "xdotool not found at configure time (scripts/install-deps.sh installs it)";
#else
  writeScript("forever.txt", "wait frames 1000000\n");
  std::ofstream(dir / "keys.sh")
      << "'" TSR_VIEWER_PATH "' builtin:animated --viewports vulkan --size 200x150 --script forever.txt &\n"
         "pid=$!\n"
         "for i in $(seq 100); do w=$(" TSR_XDOTOOL
         " search --name tessera-viewer | head -1); [ -n \"$w\" ] && break; sleep 0.2; done\n" TSR_XDOTOOL
         " windowfocus --sync $w\n" TSR_XDOTOOL " mousemove --window $w 50 50\n"
         "sleep 0.5\n" TSR_XDOTOOL " key b\n" TSR_XDOTOOL " key F12\n"
         "for i in $(seq 100); do [ -f viewer-1-0.png ] && break; sleep 0.2; done\n" TSR_XDOTOOL " key Escape\n"
         "wait $pid\n";
  const Outcome v = runBinary("/bin/sh", "keys.sh");
  EXPECT_EQ(v.status, 0) << v.err;
  EXPECT_THAT(v.out, HasSubstr("viewport 0: vulkan, scene converted"));
  EXPECT_THAT(v.out, HasSubstr("viewport 0: coverage, scene converted")) << "B went from vulkan to the next name";
  ASSERT_TRUE(std::filesystem::exists(dir / "viewer-1-0.png")) << v.out << v.err;
  EXPECT_EQ(image("viewer-1-0.png").width, 200u);
#endif
}

// The swapchain copy, the panels' render pass and the window read-back
// under Vulkan's validation layers, through a resize-free run.
TEST_F(ViewerWindow, PresentsPanelsWithoutValidationErrors) {
  writeScript("valid.txt", "wait frames 3\nwindow-screenshot w.png\nbackend 0 coverage\nwait frames 2\n");
  const Outcome v =
      viewer("builtin:animated --viewports vulkan --size 320x200 --validate --script valid.txt --exit-after");
  EXPECT_EQ(v.status, 0) << v.err;
  EXPECT_THAT(v.err, ::testing::Not(HasSubstr("error")));
}

TEST_F(ViewerWindow, AFailingActionNamesItsLine) {
  writeScript("fail.txt", "wait frames 1\nbookmark load nowhere\n");
  const Outcome v = viewer("builtin:cornell --viewports vulkan --size 64x64 --script fail.txt --exit-after");
  EXPECT_EQ(v.status, 2);
  EXPECT_THAT(v.err, HasSubstr("error: fail.txt:2: no bookmark 'nowhere'"));
  // A parameter no back-end takes, in a script, names the line and the valid ones.
  writeScript("typo.txt", "wait frames 1\nparam 0 sigmaSS=4\n");
  const Outcome t = viewer("builtin:cornell --viewports vulkan --size 64x64 --script typo.txt --exit-after");
  EXPECT_EQ(t.status, 2);
  EXPECT_THAT(t.err, HasSubstr("error: typo.txt:2: unknown parameter 'sigmaSS'"));
  const Outcome o = viewer("builtin:cornell --viewports vulkan --size 64x64 --param sigmaSS=4");
  EXPECT_EQ(o.status, 2);
  EXPECT_THAT(o.err, HasSubstr("unknown parameter 'sigmaSS'"));
  // Waiting for samples while the animation plays would hang: refused.
  writeScript("playing.txt", "wait samples 2\n");
  const Outcome p = viewer("builtin:animated --viewports embree --size 32x32 --script playing.txt --exit-after");
  EXPECT_EQ(p.status, 2);
  EXPECT_THAT(p.err, HasSubstr("error: playing.txt:1: wait samples while the animation plays would never end"));
}

// --cluster: viewport 0's path tracer renders on two real tessera-node
// processes; the picture equals tessera-render --cluster's of the same view
// (same config, same nodes: bit for bit), and follows the camera.
TEST_F(ViewerWindow, ClusterClientRendersOnNodes) {
  tsr::cluster::test::TokenFile token("viewer token");
  auto nodes = tsr::cluster::test::startNodes(2, {"--token-file", token.path()});
  const std::string cluster = std::string(" --cluster ") + TSR_CONFIG_DIR + "/cooperative-2.json --nodes " +
                              nodes[0]->text() + "," + nodes[1]->text() + " --token-file " + token.path();
  writeScript("cluster.txt",
              "time 0\nwait frames 2\nscreenshot cluster.png\norbit 20\nwait frames 2\nscreenshot turned.png\n");
  const Outcome v = viewer("builtin:animated --size 96x72" + cluster + " --script cluster.txt --exit-after");
  ASSERT_EQ(v.status, 0) << v.err;
  EXPECT_THAT(v.out, HasSubstr("2 of 2 nodes online"));
  const Outcome r = render("builtin:animated --size 96x72 --quiet --filter pixel --output ref.png" + cluster);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto shot = image("cluster.png");
  EXPECT_GT(litFraction(shot), 0.3);
  EXPECT_LE(compare(shot, image("ref.png")).maxAbs, 1.0 / 255 + 1e-6);
  EXPECT_GT(compare(shot, image("turned.png")).meanAbs, 0.03);
}

// The workload overlay (O, or the script's "workload on"): viewport 0 shows
// over its picture which node rendered which tile. cooperative-2.json cuts
// 96x72 into 32-pixel tiles, the first five (the top row and more) to node
// 0, drawn orange, the last four (the bottom row) to node 1, sky blue.
TEST_F(ViewerWindow, ClusterWorkloadOverlayShowsEachTilesNode) {
  tsr::cluster::test::TokenFile token("viewer token");
  auto nodes = tsr::cluster::test::startNodes(2, {"--token-file", token.path()});
  const std::string cluster = std::string(" --cluster ") + TSR_CONFIG_DIR + "/cooperative-2.json --nodes " +
                              nodes[0]->text() + "," + nodes[1]->text() + " --token-file " + token.path();
  writeScript("workload.txt", "time 0\nwait frames 2\nwindow-screenshot plain.png\nworkload on\nwait frames 1\n"
                              "window-screenshot over.png\n");
  const Outcome v =
      viewer("builtin:animated --size 96x72 --hide-panels" + cluster + " --script workload.txt --exit-after");
  ASSERT_EQ(v.status, 0) << v.err;
  const auto plain = image("plain.png"), over = image("over.png");
  ASSERT_EQ(over.width, 96u);
  // Red over blue in a band of rows, the overlay's minus the picture's.
  auto redOverBlue = [&](std::uint32_t y0, std::uint32_t y1) {
    double sum = 0;
    for (std::uint32_t y = y0; y < y1; ++y)
      for (std::uint32_t x = 0; x < 96; ++x) {
        const glm::vec4 a = over.colour[over.index(x, y)], b = plain.colour[plain.index(x, y)];
        sum += (a.r - a.b) - (b.r - b.b);
      }
    return sum / double((y1 - y0) * 96);
  };
  EXPECT_GT(redOverBlue(0, 32), 0.05) << "node 0's tiles are not drawn orange";
  EXPECT_LT(redOverBlue(64, 72), -0.05) << "node 1's tiles are not drawn sky blue";
}

}  // namespace
