#include "test_util.hpp"

#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"

#include <gtest/gtest.h>

namespace tsr::vk {
namespace {

using test::device;

// A ground plane with a small square occluder hovering over the origin; the
// camera sees the origin past the occluder's edge.
struct ShadowScene {
  Scene scene{device()};
  Camera cam = Camera::lookAt({0, 4, 4}, {0, 0, 0}, {0, 1, 0}, 0.9f, 1.0f);
  Region full = Region::full(64, 64);

  ShadowScene() {
    Material m;
    m.baseColor = glm::vec3(0.5f);
    MaterialId mat = scene.addMaterial(m);
    scene.addInstance(scene.addMesh(test::groundQuad(0, 0, 3)), mat, glm::mat4(1.0f));
    scene.addInstance(scene.addMesh(test::groundQuad(0, 0, 0.5f, 1.0f)), mat, glm::mat4(1.0f));
  }

  glm::vec4 at(const FrameBuffer& fb, glm::vec3 p) const {
    glm::vec2 px = test::project(cam, full, p);
    return fb.colour(int(px.x), int(px.y));
  }

  void check(const Light& light, const char* name) {
    LightId id = scene.addLight(light);
    FrameBuffer on(64, 64), off(64, 64);
    Renderer renderer(device(), {.shadows = true, .shadowMapSize = 512});
    renderer.render(scene, cam, full, on);
    EXPECT_EQ(renderer.lastStats().shadowMaps, 1u) << name;
    test::writePng(std::string("/tmp/tsr_vk_shadow_") + name + ".png", on);
    renderer.setSettings({.shadows = false});
    renderer.render(scene, cam, full, off);
    EXPECT_EQ(renderer.lastStats().shadowMaps, 0u) << name;

    const glm::vec3 shadowed(0.1f, 0.0f, -0.1f), lit(1.5f, 0.0f, 0.5f);
    const float litOn = at(on, lit).r, litOff = at(off, lit).r;
    EXPECT_GT(litOn, 0.05f) << name;
    EXPECT_NEAR(litOn, litOff, 1e-3f * litOff) << name;  // no self-shadowing (acne)
    EXPECT_LT(at(on, shadowed).r, 0.02f * at(off, shadowed).r) << name;
    EXPECT_GT(at(off, shadowed).r, 0.05f) << name;
    scene.removeLight(id);
  }
};

TEST(VulkanShadow, DirectionalOccluderDarkensGroundBelow) {
  ShadowScene s;
  s.check(DirectionalLight{{0, -1, 0}, glm::vec3(3.0f)}, "directional");
}

TEST(VulkanShadow, SpotOccluderDarkensGroundBelow) {
  ShadowScene s;
  SpotLight spot;
  spot.position = {0, 3, 0};
  spot.direction = {0, -1, 0};
  spot.intensity = glm::vec3(20.0f);
  spot.innerAngle = 0.6f;
  spot.outerAngle = 0.8f;
  s.check(spot, "spot");
}

TEST(VulkanShadow, LightThatCastsNoShadowsGetsNoShadowMap) {
  ShadowScene s;
  DirectionalLight d{{0, -1, 0}, glm::vec3(3.0f)};
  d.castShadows = false;
  s.scene.addLight(d);
  s.scene.addLight(PointLight{{0, 3, 0}, glm::vec3(5.0f)});
  Renderer renderer(device());
  FrameBuffer fb(64, 64);
  renderer.render(s.scene, s.cam, s.full, fb);
  EXPECT_EQ(renderer.lastStats().shadowMaps, 0u);
  EXPECT_GT(s.at(fb, {0.1f, 0.0f, -0.1f}).r, 0.1f);
}

// Shadow maps do not depend on the camera: a renderer keeps them until the
// scene or the light changes, and the image is the one a fresh renderer makes.
TEST(VulkanShadow, MapsAreKeptWhileOnlyTheCameraMoves) {
  ShadowScene s;
  const LightId light = s.scene.addLight(DirectionalLight{{0.3f, -1, 0.2f}, glm::vec3(3.0f)});
  const Camera other = Camera::lookAt({3, 3, 1}, {0, 0, 0}, {0, 1, 0}, 0.9f, 1.0f);
  Renderer renderer(device());
  FrameBuffer kept(64, 64), fresh(64, 64);
  renderer.render(s.scene, s.cam, s.full, kept);
  EXPECT_EQ(renderer.lastStats().shadowMaps, 1u);
  renderer.render(s.scene, other, s.full, kept);
  EXPECT_EQ(renderer.lastStats().shadowMaps, 0u);
  Renderer(device()).render(s.scene, other, s.full, fresh);
  EXPECT_EQ(kept.colourImage(), fresh.colourImage());

  s.scene.setLight(light, DirectionalLight{{-0.3f, -1, 0.2f}, glm::vec3(3.0f)});
  renderer.render(s.scene, other, s.full, kept);
  EXPECT_EQ(renderer.lastStats().shadowMaps, 1u) << "the light moved";
  Renderer(device()).render(s.scene, other, s.full, fresh);
  EXPECT_EQ(kept.colourImage(), fresh.colourImage());
}

}  // namespace
}  // namespace tsr::vk
