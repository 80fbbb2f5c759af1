// The thin-lens camera (issue 30): a pinhole when the aperture is 0 (bit
// for bit), points on the plane in focus stay sharp, and a small light off
// that plane spreads into the circle of confusion the lens equation gives.
#include "test_scenes.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tsr::embree::test {
namespace {

constexpr std::uint32_t kSide = 64;
constexpr float kFov = 0.6f;  // radians, vertical

Material lamp(const glm::vec3& emission) {
  Material m;
  m.baseColor = glm::vec3(0.0f);
  m.emission = emission;
  return m;
}

// A small lamp (a sphere of radius 0.05) at depth `depth` in front of the
// camera, nothing else, seen through a lens of `aperture` focused at `focus`.
FrameBuffer renderLamp(float depth, float aperture, float focus, std::uint32_t spp = 64) {
  Scene scene(sharedDevice());
  scene.addInstance(scene.addMesh(uvSphere({0, 0, -depth}, 0.05f, 800, true)), scene.addMaterial(lamp(glm::vec3(1.0f))),
                    glm::mat4(1.0f));
  RenderSettings s;
  s.samplesPerPass = 8;
  Renderer renderer(s);
  Camera camera = Camera::lookAt({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, kFov, 1.0f);
  camera.apertureRadius = aperture;
  camera.focusDistance = focus;
  FrameBuffer fb(kSide, kSide);
  render(renderer, scene, camera, Region::full(kSide, kSide), fb, spp / 8);
  return fb;
}

// The image's intensity-weighted second moment about its centre, in pixels^2.
double secondMoment(const FrameBuffer& fb) {
  double sum = 0.0, weighted = 0.0;
  for (std::uint32_t y = 0; y < kSide; ++y)
    for (std::uint32_t x = 0; x < kSide; ++x) {
      const double l = fb.colour(x, y).g;
      const double dx = x + 0.5 - kSide / 2.0, dy = y + 0.5 - kSide / 2.0;
      sum += l;
      weighted += l * (dx * dx + dy * dy);
    }
  return weighted / sum;
}

TEST(EmbreeThinLens, ZeroApertureIsThePinholeBitForBit) {
  const FrameBuffer pinhole = renderLamp(3.0f, 0.0f, 1.0f, 8), other = renderLamp(3.0f, 0.0f, 7.5f, 8);
  for (std::uint32_t y = 0; y < kSide; ++y)
    for (std::uint32_t x = 0; x < kSide; ++x) ASSERT_EQ(pinhole.colour(x, y), other.colour(x, y));
}

TEST(EmbreeThinLens, ThePlaneInFocusStaysSharp) {
  const double pinhole = secondMoment(renderLamp(3.0f, 0.0f, 3.0f));
  const double focused = secondMoment(renderLamp(3.0f, 0.2f, 3.0f));
  EXPECT_NEAR(focused, pinhole, 0.05 * pinhole) << "the lamp on the plane in focus";
  const double blurred = secondMoment(renderLamp(3.0f, 0.2f, 1.5f));
  EXPECT_GT(blurred, 4.0 * pinhole) << "the same lamp with the focus elsewhere";
}

// A point at depth z seen through a lens of radius A focused at f lands on
// a disc of radius A |1/f - 1/z| in units of the window at distance 1, i.e.
// A |1/f - 1/z| H / (2 tan(fov / 2)) pixels. A uniform disc of radius R has
// a second moment of R^2 / 2, and the lamp's own small disc adds its own.
TEST(EmbreeThinLens, AnOutOfFocusPointSpreadsIntoTheCircleOfConfusion) {
  for (const auto& [depth, focus] : {std::pair{4.0f, 2.0f}, std::pair{2.0f, 4.0f}, std::pair{6.0f, 2.5f}}) {
    const float aperture = 0.4f;
    const double expected = aperture * std::abs(1.0 / focus - 1.0 / depth) * kSide / (2.0 * std::tan(kFov / 2.0));
    const FrameBuffer fb = renderLamp(depth, aperture, focus, 256);
    const double own = secondMoment(renderLamp(depth, 0.0f, focus));  // the lamp's own disc, and the pixels'
    const double radius = std::sqrt(2.0 * std::max(0.0, secondMoment(fb) - own));
    EXPECT_NEAR(radius, expected, 0.05 * expected) << "lamp at " << depth << ", focus at " << focus;
  }
}

}  // namespace
}  // namespace tsr::embree::test
