// What pixel filtering reads from the renderer: paths classified relative
// to the first non-specular surface, and the "virtual flash" range colour.
#include "test_scenes.hpp"

#include <gtest/gtest.h>

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
  // Nothing hit: black.
  EXPECT_EQ(fb.rangeColour(kSize / 2, 0), glm::vec3(0.0f));
}

TEST(EmbreeFilterInputs, FlashFollowsPerfectSpecularSurfaces) {
  // A mirror facing the camera reflects the red wall behind the camera.
  Scene scene(sharedDevice());
  Material mirror;
  mirror.type = MaterialType::Mirror;
  mirror.baseColor = glm::vec3(1.0f);
  scene.addInstance(scene.addMesh(quad({-2, -2, -2}, {2, -2, -2}, {2, 2, -2}, {-2, 2, -2})), scene.addMaterial(mirror),
                    glm::mat4(1.0f));
  Material red;
  red.baseColor = glm::vec3(0.8f, 0.1f, 0.1f);
  scene.addInstance(scene.addMesh(quad({-9, -9, 3}, {-9, 9, 3}, {9, 9, 3}, {9, -9, 3})), scene.addMaterial(red),
                    glm::mat4(1.0f));
  Camera camera = Camera::lookAt({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, glm::radians(30.0f), 1.0f);
  Renderer renderer;
  FrameBuffer fb(16, 16);
  renderer.renderFlashPass(scene, camera, Region::full(16, 16), fb, 4);
  const glm::vec3 c = fb.rangeColour(8, 8);
  // Reflected straight back: the red wall faces the eye, so ambient + head light = full reflectivity.
  EXPECT_NEAR(c.x, 0.8f, 0.02f);
  EXPECT_NEAR(c.y, 0.1f, 0.01f);
}

}  // namespace
}  // namespace tsr::embree::test
