// Motion blur (issue 30): instances with two time steps and rays with a
// time. An object moving at constant speed leaves a streak as long as its
// screen displacement over the shutter; a camera moving the other way
// leaves the same streak; a shutter that is an instant changes nothing of
// a still scene; and the image stays the same across threads and tiles.
#include "test_scenes.hpp"
#include "tsr/backend/validate.hpp"
#include "tsr/embree/error.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace tsr::embree::test {
namespace {

constexpr std::uint32_t kSide = 64;
constexpr float kFov = 0.6f;    // radians, vertical
constexpr float kDepth = 3.0f;  // of the lamp, in front of the camera

// The lamp's screen displacement in pixels for a world displacement d at kDepth.
double pixels(float d) { return d / kDepth * kSide / (2.0 * std::tan(kFov / 2.0)); }

struct Shot {
  float travel = 0.0f;        // how far the lamp moves along x over the frame interval
  float cameraTravel = 0.0f;  // how far the camera moves along x
  float open = 0.0f, close = 0.0f;
  std::uint32_t spp = 64;
  int threads = 0;
  Region region = Region::full(kSide, kSide);
};

// A small lamp (a sphere of radius 0.05) at the centre of the view, nothing
// else, moving along x.
FrameBuffer renderLamp(const Shot& shot) {
  Scene scene(sharedDevice());
  Material lamp;
  lamp.baseColor = glm::vec3(0.0f);
  lamp.emission = glm::vec3(1.0f);
  const InstanceId id = scene.addInstance(scene.addMesh(uvSphere({0, 0, -kDepth}, 0.05f, 800, true)),
                                          scene.addMaterial(lamp), glm::mat4(1.0f));
  // From half the travel left of the centre to half right, so the streak stays in the image.
  if (shot.travel != 0.0f)
    scene.setInstanceTransform(id, glm::translate(glm::mat4(1.0f), {-0.5f * shot.travel, 0, 0}),
                               glm::translate(glm::mat4(1.0f), {0.5f * shot.travel, 0, 0}));
  RenderSettings s;
  s.samplesPerPass = 8;
  s.threads = shot.threads;
  Renderer renderer(s);
  Camera camera = Camera::lookAt({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, kFov, 1.0f);
  camera.shutterOpen = shot.open;
  camera.shutterClose = shot.close;
  if (shot.cameraTravel != 0.0f) {
    const glm::mat4 start = camera.cameraToWorld;
    camera.cameraToWorld = glm::translate(glm::mat4(1.0f), {-0.5f * shot.cameraTravel, 0, 0}) * start;
    camera.cameraToWorldAtEnd = glm::translate(glm::mat4(1.0f), {0.5f * shot.cameraTravel, 0, 0}) * start;
  }
  FrameBuffer fb(shot.region.regionWidth(), shot.region.regionHeight());
  render(renderer, scene, camera, shot.region, fb, shot.spp / 8);
  return fb;
}

struct Spread {
  double sum = 0, meanX = 0, varianceX = 0, varianceY = 0;
};

// The image's intensity-weighted mean and variance along each axis, in pixels.
Spread spread(const FrameBuffer& fb) {
  Spread s;
  double x1 = 0, x2 = 0, y1 = 0, y2 = 0;
  for (std::uint32_t y = 0; y < fb.height(); ++y)
    for (std::uint32_t x = 0; x < fb.width(); ++x) {
      const double l = fb.colour(x, y).g, px = x + 0.5, py = y + 0.5;
      s.sum += l;
      x1 += l * px, x2 += l * px * px, y1 += l * py, y2 += l * py * py;
    }
  s.meanX = x1 / s.sum;
  s.varianceX = x2 / s.sum - s.meanX * s.meanX;
  s.varianceY = y2 / s.sum - (y1 / s.sum) * (y1 / s.sum);
  return s;
}

// A uniform streak of length L adds L^2 / 12 to the still lamp's variance.
double streakLength(const Spread& blurred, const Spread& still) {
  return std::sqrt(12.0 * std::max(0.0, blurred.varianceX - still.varianceX));
}

TEST(EmbreeMotionBlur, AnInstantShutterLeavesAStillSceneBitForBit) {
  const FrameBuffer today = renderLamp({.spp = 8}), instant = renderLamp({.open = 0.4f, .close = 0.4f, .spp = 8});
  EXPECT_TRUE(identical(today, instant));
}

TEST(EmbreeMotionBlur, AStreakIsAsLongAsTheScreenDisplacementOverTheShutter) {
  const Spread still = spread(renderLamp({}));
  for (const auto& [open, close] : {std::pair{0.0f, 1.0f}, std::pair{0.25f, 0.75f}}) {
    const float travel = 1.0f;
    const Spread blurred = spread(renderLamp({.travel = travel, .open = open, .close = close, .spp = 256}));
    const double expected = pixels(travel) * (close - open);
    EXPECT_NEAR(streakLength(blurred, still), expected, 0.05 * expected) << "shutter " << open << "," << close;
    // The streak lies where the lamp was while the shutter was open ...
    EXPECT_NEAR(blurred.meanX - still.meanX, pixels(travel) * (0.5 * (open + close) - 0.5), 0.5);
    // ... keeps its height, and spreads the lamp's light without losing any.
    EXPECT_NEAR(blurred.varianceY, still.varianceY, 0.1 * still.varianceY + 0.05);
    EXPECT_NEAR(blurred.sum, still.sum, 0.03 * still.sum);
  }
}

TEST(EmbreeMotionBlur, AnInstantShutterShowsTheMovingObjectWhereItIsThen) {
  const Spread still = spread(renderLamp({}));
  const Spread instant = spread(renderLamp({.travel = 1.0f, .open = 0.75f, .close = 0.75f}));
  EXPECT_NEAR(instant.meanX - still.meanX, pixels(1.0f) * 0.25, 0.25);
  EXPECT_NEAR(instant.varianceX, still.varianceX, 0.1 * still.varianceX + 0.05) << "an instant is sharp";
}

TEST(EmbreeMotionBlur, ACameraMovingTheOtherWayLeavesTheSameStreak) {
  const Spread still = spread(renderLamp({}));
  const Spread lampMoves = spread(renderLamp({.travel = 0.8f, .close = 1.0f, .spp = 256}));
  const Spread cameraMoves = spread(renderLamp({.cameraTravel = -0.8f, .close = 1.0f, .spp = 256}));
  const double expected = pixels(0.8f);
  EXPECT_NEAR(streakLength(cameraMoves, still), expected, 0.05 * expected);
  EXPECT_NEAR(cameraMoves.meanX, lampMoves.meanX, 0.5);
}

// A lamp bar turning a quarter turn about the view axis over the frame,
// seen at one instant of it. Embree interpolates the turn as a rotation
// (InstanceMotion), so mid-turn the bar keeps its size: blending the two
// matrices would shrink it to cos 45° across, half its area.
FrameBuffer renderBar(float startDegrees, float endDegrees, float instant) {
  Scene scene(sharedDevice());
  Material lamp;
  lamp.baseColor = glm::vec3(0.0f);
  lamp.emission = glm::vec3(1.0f);
  const InstanceId id = scene.addInstance(scene.addMesh(box({-0.5f, -0.05f, -0.05f}, {0.5f, 0.05f, 0.05f})),
                                          scene.addMaterial(lamp), glm::mat4(1.0f));
  auto pose = [](float degrees) {
    return glm::rotate(glm::translate(glm::mat4(1.0f), {0, 0, -kDepth}), glm::radians(degrees), {0, 0, 1});
  };
  scene.setInstanceTransform(id, pose(startDegrees), pose(endDegrees));
  RenderSettings s;
  s.samplesPerPass = 8;
  Renderer renderer(s);
  Camera camera = Camera::lookAt({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, kFov, 1.0f);
  camera.shutterOpen = camera.shutterClose = instant;
  FrameBuffer fb(kSide, kSide);
  render(renderer, scene, camera, Region::full(kSide, kSide), fb, 8);
  return fb;
}

TEST(EmbreeMotionBlur, ATurningObjectKeepsItsSizeMidTurn) {
  const Spread still = spread(renderBar(45.0f, 45.0f, 0.0f));
  const Spread mid = spread(renderBar(0.0f, 90.0f, 0.5f));
  EXPECT_NEAR(mid.sum, still.sum, 0.03 * still.sum) << "the bar's area mid-turn";
  EXPECT_NEAR(mid.varianceX, still.varianceX, 0.05 * still.varianceX) << "and its extent";
}

TEST(EmbreeMotionBlur, BlurredImagesAreTheSameAcrossThreadsAndTiles) {
  const Shot shot{.travel = 1.0f, .cameraTravel = 0.2f, .open = 0.1f, .close = 0.9f, .spp = 16};
  Shot oneThread = shot, crop = shot;
  oneThread.threads = 1;
  crop.region = Region{kSide, kSide, 20, 24, 52, 40};
  const FrameBuffer full = renderLamp(shot);
  EXPECT_TRUE(identical(full, renderLamp(oneThread)));
  EXPECT_TRUE(identical(full, renderLamp(crop), 20, 24));
}

TEST(EmbreeMotionBlur, AShutterOutsideTheFrameIntervalIsRefused) {
  Camera camera = Camera::lookAt({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, kFov, 1.0f);
  for (const auto& [open, close] : {std::pair{-0.1f, 0.5f}, std::pair{0.6f, 0.5f}, std::pair{0.0f, 1.5f}}) {
    camera.shutterOpen = open;
    camera.shutterClose = close;
    EXPECT_THROW(backend::validate<Error>(camera), Error) << open << "," << close;
  }
}

}  // namespace
}  // namespace tsr::embree::test
