// What a new user tries first, through tessera-render with the real
// back-ends: a scene lit only by emissive geometry and a glTF without any
// lights both render recognisably lit in the path tracer and the
// rasterizer; cameras are chosen by name or index, placed from the command
// line, and moved by their animated parents; exposure and the filmic curve
// change PNGs only; bad values are one error line.
#include <cmath>
#include <fstream>
#include <sstream>

#include <glm/glm.hpp>

#include "command_runner.hpp"
#include "lit_scene_gltf.hpp"
#include "tsr/med/image_file.hpp"

namespace {

using ::testing::HasSubstr;
using tsr::test::Outcome;

// Brightness: mean luminance of the colour clamped to [0, 1], as a PNG
// shows it (unclamped, the emitter's own pixels would dominate). Embree (64
// spp) over vulkan, measured (docs/rendering.md, "Lights, cameras and the picture"):
// builtin:cornell 1.05, the boxes under the default rig 1.00. Allowed:
// within a factor of 1.3 either way.
constexpr double kBrightnessFactor = 1.3;

class FirstHour : public tsr::test::CommandTest {
 protected:
  Outcome run(const std::string& args) { return runBinary(TSR_RENDER_PATH, args); }
  void render(const std::string& args) {
    const Outcome r = run(args + " --quiet");
    ASSERT_EQ(r.status, 0) << args << "\n" << r.err;
  }
  tsr::med::FrameBuffer image(const std::string& name) { return tsr::med::readImage((dir / name).string()); }
  static double meanLuminance(const tsr::med::FrameBuffer& fb) {
    double sum = 0;
    for (const auto& p : fb.colour) {
      const glm::vec3 c = glm::clamp(glm::vec3(p), 0.0f, 1.0f);
      sum += 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    }
    return sum / double(fb.colour.size());
  }
  static double meanAbsDifference(const tsr::med::FrameBuffer& a, const tsr::med::FrameBuffer& b) {
    EXPECT_EQ(a.colour.size(), b.colour.size());
    if (a.colour.size() != b.colour.size()) return 1e9;
    double sum = 0;
    for (std::size_t i = 0; i < a.colour.size(); ++i)
      for (int c = 0; c < 3; ++c) sum += std::abs(a.colour[i][c] - b.colour[i][c]);
    return sum / (3.0 * double(a.colour.size()));
  }
  static void expectSimilarBrightness(double embree, double vulkan, const std::string& scene) {
    ASSERT_GT(vulkan, 0.0) << scene;
    const double ratio = embree / vulkan;
    std::cout << scene << ": mean luminance embree " << embree << ", vulkan " << vulkan << ", ratio " << ratio << "\n";
    EXPECT_LT(ratio, kBrightnessFactor) << scene;
    EXPECT_GT(ratio, 1.0 / kBrightnessFactor) << scene;
  }
  std::string boxes() {
    tsr::test::writeLitSceneGltf((dir / "boxes.gltf").string());
    return "boxes.gltf --size 64x48";
  }
  // The camera's vertical field of view in degrees, as --fov takes it.
  static std::string fov() { return std::to_string(glm::degrees(double(tsr::test::kCameraYfov))); }
};

TEST_F(FirstHour, CornellIsLitByItsCeilingPanelInEmbreeAndVulkan) {
  const std::string common = "builtin:cornell --size 64x64 ";
  render(common + "--backend embree --spp 64 --seed 1 --output e.exr");
  render(common + "--backend vulkan --output v.exr");
  // Nor bounced light: the path tracer's probes carry the panel's light too.
  render(common + "--backend vulkan --param emitterLights=0 --param bouncedLight=ambient --output unlit.exr");
  const double embree = meanLuminance(image("e.exr")), vulkan = meanLuminance(image("v.exr"));
  expectSimilarBrightness(embree, vulkan, "builtin:cornell");
  // Without emitter lights only the panel itself shows (the black room).
  EXPECT_LT(meanLuminance(image("unlit.exr")), 0.2 * vulkan);
  // The same room in both: floor and ceiling lit, red wall left, green right.
  for (const char* name : {"e.exr", "v.exr"}) {
    const auto fb = image(name);
    const auto at = [&](int x, int y) { return glm::vec3(fb.colour[std::size_t(y) * fb.width + x]); };
    EXPECT_GT(at(10, 60).r, 0.1f) << name << ": the floor is lit";
    EXPECT_GT(at(32, 5).g, 0.1f) << name << ": the ceiling is lit";
    EXPECT_GT(at(4, 30).r, 2 * at(4, 30).g) << name << ": the left wall is red";
    EXPECT_GT(at(60, 30).g, 2 * at(60, 30).r) << name << ": the right wall is green";
  }
}

TEST_F(FirstHour, AGltfWithoutLightsGetsTheDefaultRigInEveryBackend) {
  const std::string scene = boxes();
  const Outcome e = run(scene + " --backend embree --spp 64 --seed 1 --output e.exr --quiet");
  ASSERT_EQ(e.status, 0) << e.err;
  EXPECT_THAT(e.out, HasSubstr("default rig")) << "the log says the scene got the default rig";
  render(scene + " --backend vulkan --output v.exr");
  expectSimilarBrightness(meanLuminance(image("e.exr")), meanLuminance(image("v.exr")), "boxes.gltf");
  // The coverage back-end shows false colours, not light: it renders, with the rig's nodes ignored.
  render(scene + " --backend coverage --output c.png");
  // --no-default-light: nothing lights it, in either.
  render(scene + " --backend embree --spp 4 --no-default-light --output e0.exr");
  render(scene + " --backend vulkan --no-default-light --output v0.exr");
  EXPECT_EQ(meanLuminance(image("e0.exr")), 0.0);
  EXPECT_EQ(meanLuminance(image("v0.exr")), 0.0);
  // Builtin:cornell has its own light: no rig there.
  const Outcome c = run("builtin:cornell --size 8x8 --backend vulkan --output c.exr --quiet");
  EXPECT_THAT(c.out, ::testing::Not(HasSubstr("default rig")));
}

TEST_F(FirstHour, CamerasAreChosenByNameOrIndexAndPlacedByLookOptions) {
  const std::string scene = boxes() + " --backend vulkan";
  render(scene + " --output first.exr");
  render(scene + " --camera front --output front.exr");
  render(scene + " --camera 1 --output one.exr");
  render(scene + " --camera top --output top.exr");
  EXPECT_EQ(meanAbsDifference(image("first.exr"), image("front.exr")), 0.0) << "the first camera is the default";
  EXPECT_EQ(meanAbsDifference(image("one.exr"), image("top.exr")), 0.0) << "index 1 is the camera named top";
  EXPECT_GT(meanAbsDifference(image("front.exr"), image("top.exr")), 0.02) << "top sees another view";
  // The front camera's pose by hand: the same view (planes differ, pixels hardly).
  render(scene + " --look-from 0,1.5,6 --look-at 0,1.5,0 --fov " + fov() + " --output look.exr");
  EXPECT_LT(meanAbsDifference(image("front.exr"), image("look.exr")), 2e-3);
  // --fov alone widens the chosen camera's view: the boxes get smaller.
  render(scene + " --fov 90 --output wide.exr");
  EXPECT_GT(meanAbsDifference(image("front.exr"), image("wide.exr")), 0.02);
}

// Depth of field from the command line: focused on the boxes (6 units away)
// they stay as the pinhole shows them; focused near the camera they blur.
// An aperture of 0 is the pinhole, bit for bit.
TEST_F(FirstHour, ApertureAndFocusDistanceGiveDepthOfField) {
  const std::string scene = boxes() + " --backend embree --spp 16 --seed 5";
  render(scene + " --output pinhole.exr");
  render(scene + " --aperture 0 --focus-distance 2 --output zero.exr");
  render(scene + " --aperture 0.3 --focus-distance 6 --output focused.exr");
  render(scene + " --aperture 0.3 --focus-distance 1 --output blurred.exr");
  EXPECT_EQ(meanAbsDifference(image("pinhole.exr"), image("zero.exr")), 0.0);
  const double sharp = meanAbsDifference(image("pinhole.exr"), image("focused.exr"));
  const double blurred = meanAbsDifference(image("pinhole.exr"), image("blurred.exr"));
  EXPECT_GT(blurred, 2.0 * sharp) << "out of focus differs from the pinhole far more than in focus";
  // --focus-on X,Y focuses at the depth that pixel sees: the same image as
  // --focus-distance with the depth a pinhole render's depth output shows there.
  render(scene + " --aov depth --output probe.exr");
  const auto depth = image("probe.depth.exr");
  std::ostringstream d;
  d.precision(9);
  d << depth.colour[depth.index(20, 30)].r;
  render(scene + " --aperture 0.3 --focus-on 20,30 --output on.exr");
  render(scene + " --aperture 0.3 --focus-distance " + d.str() + " --output at.exr");
  // (The depth output of 16 samples may differ from one sample's in the last bit.)
  EXPECT_LT(meanAbsDifference(image("on.exr"), image("at.exr")), 1e-6) << "focus at " << d.str();
  // --f-number N is the radius a full-frame camera's focal length at this
  // field of view gives: 12 mm / tan(fov / 2) / (2 N).
  std::ostringstream radius;
  radius.precision(9);
  radius << 0.012f / std::tan(0.5f * glm::radians(40.0f)) / (2.0f * 0.25f);
  render(scene + " --fov 40 --f-number 0.25 --focus-distance 1 --output f.exr");
  render(scene + " --fov 40 --aperture " + radius.str() + " --focus-distance 1 --output radius.exr");
  EXPECT_EQ(meanAbsDifference(image("f.exr"), image("radius.exr")), 0.0) << "radius " << radius.str();
  render(scene + " --fov 40 --focus-distance 1 --output f-pinhole.exr");
  EXPECT_GT(meanAbsDifference(image("f.exr"), image("f-pinhole.exr")), 0.0);
  for (const char* bad : {"--f-number 0", "--f-number -2", "--f-number 2 --aperture 0.1"}) {
    const Outcome r = run(scene + " " + bad + " --output bad.exr");
    EXPECT_NE(r.status, 0) << bad;
    EXPECT_NE(r.err.find("--f-number"), std::string::npos) << bad << ": " << r.err;
  }
}

// --shutter OPEN,CLOSE blurs what the animation moves over that part of
// each frame; 0,0 (an instant) is the render without it, bit for bit.
TEST_F(FirstHour, ShutterBlursWhatTheAnimationMoves) {
  const std::string scene = "builtin:animated --size 48x48 --backend embree --spp 16 --seed 5 --frames 2 --fps 2";
  render(scene + " --output plain.####.exr");
  render(scene + " --shutter 0,0 --output instant.####.exr");
  render(scene + " --shutter 0,1 --output open.####.exr");
  render(scene + " --shutter 0.25,0.5 --output part.####.exr");
  EXPECT_EQ(meanAbsDifference(image("plain.0001.exr"), image("instant.0001.exr")), 0.0);
  const double open = meanAbsDifference(image("plain.0001.exr"), image("open.0001.exr"));
  const double part = meanAbsDifference(image("plain.0001.exr"), image("part.0001.exr"));
  EXPECT_GT(open, 0.0) << "the whole frame interval blurs the motion";
  EXPECT_GT(part, 0.0);
  // One image through an open shutter blurs the first frame interval's motion (1 / --fps).
  const std::string one = "builtin:animated --size 48x48 --backend embree --spp 16 --seed 5";
  render(one + " --output one.exr");
  render(one + " --shutter 0,1 --fps 2 --output one-open.exr");
  render(one + " --shutter 0,1 --fps 200 --output one-short.exr");
  const double wide = meanAbsDifference(image("one.exr"), image("one-open.exr"));
  EXPECT_GT(wide, meanAbsDifference(image("one.exr"), image("one-short.exr"))) << "a longer interval blurs more";
  const Outcome fpsAlone = run(one + " --fps 2 --output bad.exr");
  EXPECT_NE(fpsAlone.status, 0);
  EXPECT_NE(fpsAlone.err.find("--fps"), std::string::npos) << fpsAlone.err;
  // The rasterizer has no motion blur (BackendCapabilities::motionBlur):
  // it draws each frame at its time, shutter or not. (Its bounced light is
  // traced in the path tracer's scene, where the shutter makes instances
  // move and the probes' grid take in their whole path: the ambient term
  // keeps this to what the rasterizer draws.)
  const std::string raster =
      "builtin:animated --size 48x48 --backend vulkan --frames 2 --fps 2 --param bouncedLight=ambient";
  render(raster + " --output raster.####.exr");
  render(raster + " --shutter 0,1 --output raster-open.####.exr");
  EXPECT_EQ(meanAbsDifference(image("raster.0001.exr"), image("raster-open.0001.exr")), 0.0);
  for (const char* bad : {"0.5,0.2", "-1,0", "0,2", "0.5", "a,b"}) {
    const Outcome r = run(scene + " --shutter " + bad + " --output bad.####.exr");
    EXPECT_NE(r.status, 0) << bad;
    EXPECT_NE(r.err.find("--shutter"), std::string::npos) << bad << ": " << r.err;
  }
}

// With --frames every frame draws the same random numbers (noise sticks to
// the screen, as in Cycles); --seed-per-frame gives frame f seed + f.
TEST_F(FirstHour, SeedPerFrameMovesTheNoise) {
  const std::string scene = "builtin:cornell --size 32x32 --backend embree --spp 2 --seed 7 --frames 2";
  render(scene + " --output same.####.exr");
  render(scene + " --seed-per-frame --output own.####.exr");
  EXPECT_EQ(meanAbsDifference(image("same.0000.exr"), image("same.0001.exr")), 0.0) << "a still scene, one seed";
  EXPECT_EQ(meanAbsDifference(image("same.0000.exr"), image("own.0000.exr")), 0.0) << "frame 0 keeps the seed";
  EXPECT_GT(meanAbsDifference(image("own.0000.exr"), image("own.0001.exr")), 0.01) << "frame 1 draws anew";
  render("builtin:cornell --size 32x32 --backend embree --spp 2 --seed 8 --output eight.exr");
  EXPECT_EQ(meanAbsDifference(image("own.0001.exr"), image("eight.exr")), 0.0) << "frame 1 has seed 7 + 1";
}

TEST_F(FirstHour, AnAnimatedParentMovesItsCamera) {
  const std::string scene = boxes() + " --backend vulkan --camera tracking";
  render(scene + " --frames 2 --fps 1 --output f.####.exr");
  render(boxes() + " --backend vulkan --camera front --output front.exr");
  render(boxes() + " --backend vulkan --look-from 2,1.5,6 --look-at 2,1.5,0 --fov " + fov() + " --output moved.exr");
  EXPECT_LT(meanAbsDifference(image("f.0000.exr"), image("front.exr")), 2e-3) << "at t = 0 the dolly is home";
  EXPECT_GT(meanAbsDifference(image("f.0000.exr"), image("f.0001.exr")), 0.02) << "at t = 1 it has moved";
  EXPECT_LT(meanAbsDifference(image("f.0001.exr"), image("moved.exr")), 2e-3) << "2 units along +X";
}

TEST_F(FirstHour, ExposureAndFilmicCurveChangePngsOnly) {
  const std::string scene = "builtin:cornell --size 48x48 --backend vulkan ";
  render(scene + "--output plain.png");
  render(scene + "--exposure 1 --output bright.png");
  render(scene + "--exposure 3 --output over.png");
  render(scene + "--exposure 3 --tonemap filmic --output filmic.png");
  render(scene + "--output plain.exr");
  render(scene + "--exposure 3 --tonemap filmic --output graded.exr");
  // One stop is twice the light; what clips to white gains less (1.39 on this picture).
  EXPECT_GT(meanLuminance(image("bright.png")), 1.3 * meanLuminance(image("plain.png")));
  EXPECT_EQ(meanAbsDifference(image("plain.exr"), image("graded.exr")), 0.0) << "EXR stays linear";
  // Three stops over clip much of the picture to white; the filmic curve rolls it off.
  auto clipped = [&](const char* name) {
    std::size_t n = 0;
    for (const auto& p : image(name).colour) n += p.r >= 1.0f && p.g >= 1.0f && p.b >= 1.0f;
    return n;
  };
  EXPECT_GT(clipped("over.png"), 100u);
  EXPECT_LT(clipped("filmic.png"), clipped("over.png") / 4);
}

TEST_F(FirstHour, BadViewValuesAreOneErrorLine) {
  const std::string scene = boxes() + " --backend vulkan --output x.png ";
  expectOneErrorLine(run(scene + "--fov 0"), "--fov");
  expectOneErrorLine(run(scene + "--fov 180"), "--fov");
  expectOneErrorLine(run(scene + "--fov nan"), "--fov");
  expectOneErrorLine(run(scene + "--look-from 1,2"), "--look-from 1,2: expected X,Y,Z");
  expectOneErrorLine(run(scene + "--look-from 1,2,x"), "'x' is not a number");
  expectOneErrorLine(run(scene + "--look-at inf,0,0"), "--look-at");
  expectOneErrorLine(run(scene + "--look-from 1,1,1 --look-at 1,1,1"), "same point");
  expectOneErrorLine(run(scene + "--camera 7"), "cameras: 0 'front', 1 'top', 2 'tracking'");
  expectOneErrorLine(run(scene + "--camera nosuch"), "--camera nosuch");
  expectOneErrorLine(run("builtin:instances:4 --camera 1 --output x.png"), "--camera 1");
  expectOneErrorLine(run(scene + "--tonemap sepia"), "--tonemap");
  expectOneErrorLine(run(scene + "--exposure inf"), "--exposure");
  expectOneErrorLine(run(scene + "--aperture -0.1"), "--aperture");
  expectOneErrorLine(run(scene + "--focus-distance 0"), "--focus-distance");
  expectOneErrorLine(run(scene + "--focus-on 64,0"), "--focus-on 64,0: expected a pixel X,Y inside the 64x48 image");
  expectOneErrorLine(run(scene + "--focus-on 3"), "--focus-on");
  expectOneErrorLine(run(scene + "--focus-on 1,1 --focus-distance 2"), "excludes");
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

}  // namespace
