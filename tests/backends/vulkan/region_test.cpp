#include "test_util.hpp"

#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"

#include <gtest/gtest.h>

namespace tsr::vk {
namespace {

using test::device;

void buildScene(Scene& scene) {
  Material red;
  red.baseColor = {0.8f, 0.2f, 0.1f};
  Material metal;
  metal.type = MaterialType::Conductor;
  metal.baseColor = {0.9f, 0.9f, 0.7f};
  metal.roughness = 0.3f;
  MeshId sphere = scene.addMesh(test::uvSphere(20, 32, 0.8f));
  MeshId ground = scene.addMesh(test::groundQuad(0, 0, 4, -0.8f));
  scene.addInstance(sphere, scene.addMaterial(red), glm::translate(glm::mat4(1.0f), {-0.9f, 0, 0}));
  scene.addInstance(sphere, scene.addMaterial(metal), glm::translate(glm::mat4(1.0f), {0.9f, 0, -0.5f}));
  scene.addInstance(ground, scene.addMaterial({}), glm::mat4(1.0f));
  scene.addLight(PointLight{{1, 3, 2}, glm::vec3(30.0f)});
  scene.addLight(DirectionalLight{{0.5f, -1, -0.3f}, glm::vec3(1.0f)});
}

// A region renders the same pixels as that crop of the full image: the
// projection is the off-axis sub-window, so only rounding may differ.
TEST(VulkanRegion, RegionEqualsCropOfFullImage) {
  Scene scene(device());
  buildScene(scene);
  const Camera cam = Camera::lookAt({0, 1, 5}, {0, 0, 0}, {0, 1, 0}, 0.8f, 1.5f);
  const Region full = Region::full(96, 64);
  Renderer renderer(device(), {.msaaSamples = 1, .shadows = true});
  FrameBuffer whole(96, 64);
  renderer.render(scene, cam, full, whole);
  test::writePng("/tmp/tsr_vk_region_full.png", whole);

  for (Region r : {Region{96, 64, 17, 9, 71, 50}, Region{96, 64, 0, 0, 48, 32}, Region{96, 64, 60, 40, 96, 64}}) {
    FrameBuffer part(r.regionWidth(), r.regionHeight());
    renderer.render(scene, cam, r, part);
    std::size_t differing = 0;
    float worst = 0.0f;
    for (std::uint32_t y = 0; y < part.height(); ++y)
      for (std::uint32_t x = 0; x < part.width(); ++x) {
        glm::vec4 a = part.colour(x, y), b = whole.colour(x + r.x0, y + r.y0);
        float d = 0.0f;
        for (int c = 0; c < 4; ++c) d = std::max(d, std::abs(a[c] - b[c]));
        worst = std::max(worst, d);
        if (d > 1e-3f) ++differing;
        float da = part.depth(x, y), db = whole.depth(x + r.x0, y + r.y0);
        if (d > 1e-3f) continue;
        if (std::isinf(da) || std::isinf(db)) {
          EXPECT_EQ(std::isinf(da), std::isinf(db));
        } else {
          EXPECT_NEAR(da, db, 1e-4f * db);
        }
      }
    // Edge pixels whose centre lies on a triangle edge may flip; allow a handful.
    EXPECT_LE(differing, part.width() * part.height() / 200) << "worst " << worst;
  }
}

}  // namespace
}  // namespace tsr::vk
