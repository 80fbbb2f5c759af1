// What pixel filtering and the denoiser read from the renderer: paths
// classified relative to the first non-specular surface, the "virtual
// flash" range colour, and each pixel's first half of its samples.
#include "test_scenes.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <limits>
#include <vector>

namespace tsr::embree::test {
namespace {

constexpr std::uint32_t kSize = 48;

// A grey floor under a square lamp, a glass sphere between them (so light
// focused through it reaches the floor: a caustic), and a mirror wall
// behind, seen by a camera looking down at the floor.
struct CausticScene {
  Scene scene{sharedDevice()};
  Camera camera = Camera::lookAt({0, 6, 6}, {0, 0, 0}, {0, 1, 0}, glm::radians(45.0f), 1.0f);
  CausticScene(bool withGlass) {
    floorUnderLamp(scene);
    if (withGlass) {
      Material glass;
      glass.type = MaterialType::Glass;
      glass.baseColor = glm::vec3(1.0f);
      scene.addInstance(scene.addMesh(uvSphere({0, 2, 0}, 1.0f, 800, true)), scene.addMaterial(glass), glm::mat4(1.0f));
    }
  }
  FrameBuffer render(std::uint32_t passes) {
    RenderSettings s;
    s.samplesPerPass = 8;
    Renderer renderer(s);
    FrameBuffer fb(kSize, kSize);
    test::render(renderer, scene, camera, Region::full(kSize, kSize), fb, int(passes));
    return fb;
  }
};

glm::vec3 channelSum(const FrameBuffer& fb, Channel c) {
  glm::vec3 sum(0.0f);
  for (std::uint32_t y = 0; y < fb.height(); ++y)
    for (std::uint32_t x = 0; x < fb.width(); ++x) sum += fb.mean(c, x, y);
  return sum;
}

TEST(EmbreeFilterInputs, NoSpecularSurfaceMeansNoCaustics) {
  CausticScene s(false);
  FrameBuffer fb = s.render(2);
  EXPECT_EQ(channelSum(fb, Channel::Caustic), glm::vec3(0.0f));
  EXPECT_GT(channelSum(fb, Channel::Direct).x, 0.0f);
}

TEST(EmbreeFilterInputs, LightFocusedByGlassOntoTheFloorIsCausticAndIndirect) {
  CausticScene s(true);
  FrameBuffer fb = s.render(4);
  const glm::vec3 caustic = channelSum(fb, Channel::Caustic);
  EXPECT_GT(caustic.x, 0.0f);
  // Caustics are part of indirect, never of direct.
  const glm::vec3 indirect = channelSum(fb, Channel::Indirect);
  EXPECT_LE(caustic.x, indirect.x * (1.0f + 1e-5f));
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      glm::vec3 c = fb.mean(Channel::Colour, x, y), d = fb.mean(Channel::Direct, x, y),
                i = fb.mean(Channel::Indirect, x, y);
      ASSERT_NEAR(c.x, d.x + i.x, 1e-3f * (1.0f + c.x));
    }
}

TEST(EmbreeFilterInputs, FlashColourIsReflectivityUnderAmbientAndHeadLight) {
  CausticScene s(false);
  RenderSettings settings;
  Renderer renderer(settings);
  FrameBuffer fb(kSize, kSize);
  const Region region = Region::full(kSize, kSize);
  renderer.renderPass(s.scene, s.camera, region, fb);
  auto pass = renderer.renderFlashPass(s.scene, s.camera, region, fb, 4);
  EXPECT_FALSE(pass.restarted);  // the flash joins the samples already there
  EXPECT_EQ(fb.rangeSamples(kSize / 2, kSize / 2), 4u);
  renderer.renderFlashPass(s.scene, s.camera, region, fb, 4);
  EXPECT_EQ(fb.rangeSamples(kSize / 2, kSize / 2), 8u);
  // The floor's centre faces the eye at 45 degrees: 0.5 * (0.25 + 0.75 cos 45).
  const glm::vec3 centre = fb.rangeColour(kSize / 2, kSize / 2 + 4);
  const float expected = 0.5f * (0.25f + 0.75f * 0.7071f);
  EXPECT_NEAR(centre.x, expected, 0.05f);
  EXPECT_NEAR(centre.y, centre.x, 1e-6f);
  // Nothing hit: the miss colour, outside every surface's.
  EXPECT_EQ(fb.rangeColour(kSize / 2, 0), kFlashMiss);
  EXPECT_EQ(fb.rangeSpread(kSize / 2, 0), 0.0f);
}

// A quad of `facing`'s material filling the view of a camera at the
// origin, and behind the camera a red wall that the quad reflects back.
struct ReflectorScene {
  Scene scene{sharedDevice()};
  MaterialId reflector;
  Camera camera = Camera::lookAt({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, glm::radians(30.0f), 1.0f);

  explicit ReflectorScene(const Material& facing) : reflector(scene.addMaterial(facing)) {
    scene.addInstance(scene.addMesh(quad({-2, -2, -2}, {2, -2, -2}, {2, 2, -2}, {-2, 2, -2})), reflector,
                      glm::mat4(1.0f));
    Material red;
    red.baseColor = glm::vec3(0.8f, 0.1f, 0.1f);
    scene.addInstance(scene.addMesh(quad({-9, -9, 3}, {-9, 9, 3}, {9, 9, 3}, {9, -9, 3})), scene.addMaterial(red),
                      glm::mat4(1.0f));
  }
  // The centre pixel's flash colour of a fresh 16x16 buffer.
  glm::vec3 flashAtCentre() {
    Renderer renderer;
    FrameBuffer fb(16, 16);
    renderer.renderFlashPass(scene, camera, Region::full(16, 16), fb, 4);
    return fb.rangeColour(8, 8);
  }
};

TEST(EmbreeFilterInputs, FlashFollowsPerfectSpecularSurfaces) {
  Material mirror;
  mirror.type = MaterialType::Mirror;
  mirror.baseColor = glm::vec3(1.0f);
  const glm::vec3 c = ReflectorScene(mirror).flashAtCentre();
  // Reflected straight back: the red wall faces the eye, so ambient + head light = full reflectivity.
  EXPECT_NEAR(c.x, 0.8f, 0.02f);
  EXPECT_NEAR(c.y, 0.1f, 0.01f);
}

TEST(EmbreeFilterInputs, FlashShowsGlossySurfacesThemselves) {
  // A rough metal (roughness 0.3, the sphere) in front of the red
  // wall: the flash shows the metal's own colour, not the wall it
  // reflects, so the filter smooths the glossy reflection as the surface
  // blurs it instead of stopping at the edges of a mirror image. A
  // smoother metal (roughness 0.1) shows the wall in part: its reflection
  // is sharp at the scale of a few pixels.
  Material metal;
  metal.type = MaterialType::Conductor;
  metal.baseColor = glm::vec3(0.9f);
  metal.roughness = 0.3f;
  ReflectorScene s(metal);
  const glm::vec3 c = s.flashAtCentre();
  EXPECT_NEAR(c.x, 0.9f, 0.03f);
  EXPECT_NEAR(c.y, c.x, 1e-4f) << "grey, not the red wall";

  metal.roughness = 0.1f;
  s.scene.setMaterial(s.reflector, metal);
  const glm::vec3 smooth = s.flashAtCentre();
  EXPECT_GT(smooth.x, 2.0f * smooth.y) << "the red wall shows in part";
}

TEST(EmbreeFilterInputs, FlashSpreadMarksPixelsThatMixSurfaces) {
  // A white quad's edge runs through the middle of pixel column 8; the
  // background beyond it is the miss colour.
  Scene scene(sharedDevice());
  Material white;
  white.baseColor = glm::vec3(0.8f);
  scene.addInstance(scene.addMesh(quad({-4, -4, -2}, {0.01f, -4, -2}, {0.01f, 4, -2}, {-4, 4, -2})),
                    scene.addMaterial(white), glm::mat4(1.0f));
  Camera camera = Camera::lookAt({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, glm::radians(30.0f), 1.0f);
  Renderer renderer;
  FrameBuffer fb(16, 16);
  renderer.renderFlashPass(scene, camera, Region::full(16, 16), fb, 64);
  EXPECT_LT(fb.rangeSpread(4, 8), 0.01f) << "inside the quad (the head light varies a little across a pixel)";
  EXPECT_EQ(fb.rangeSpread(12, 8), 0.0f) << "background only";
  EXPECT_GT(fb.rangeSpread(8, 8), 0.5f) << "half quad, half background";
  // The range depth is the flash samples' own: the quad's where they hit it.
  EXPECT_NEAR(fb.rangeDepth(4, 8), 2.0f, 1e-3f);
  EXPECT_NEAR(fb.rangeDepth(8, 8), 2.0f, 1e-3f) << "the hits' mean, not diluted by the misses";
  EXPECT_EQ(fb.rangeDepth(12, 8), std::numeric_limits<float>::infinity());
}

// The first half: at every count n, the mean of colour - emitted over the
// first bit_floor(n) / 2 samples.
TEST(EmbreeFilterInputs, FirstHalfIsTheMeanOfTheFirstHalfOfThePowerOfTwoSamples) {
  FrameBuffer fb(1, 1);
  std::vector<glm::vec3> scattered;
  for (std::uint32_t n = 1; n <= 13; ++n) {
    PixelSample s;
    s.direct = glm::vec3(float(n), 2.0f * float(n), 0.5f);
    s.emitted = n % 3 == 0 ? glm::vec3(1.0f) : glm::vec3(0.0f);
    s.direct += s.emitted;
    fb.accumulate(0, 0, s);
    scattered.push_back(s.direct - s.emitted);
    const std::uint32_t half = std::bit_floor(n) / 2;
    ASSERT_EQ(fb.firstHalfCount(0, 0), half) << n;
    if (half == 0) continue;
    glm::vec3 mean(0.0f);
    for (std::uint32_t k = 0; k < half; ++k) mean += scattered[k] / float(half);
    EXPECT_NEAR(fb.firstHalf(0, 0).x, mean.x, 1e-4f) << n;
    EXPECT_NEAR(fb.firstHalf(0, 0).y, mean.y, 1e-4f) << n;
  }
  EXPECT_NEAR(fb.emitted(0, 0).x, 4.0f / 13.0f, 1e-5f);
}

}  // namespace
}  // namespace tsr::embree::test
