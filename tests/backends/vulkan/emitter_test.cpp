// Emissive geometry as light in the rasterizer (src/emitter_lights.hpp):
// the patches a mesh is cut into keep its area and orientation, clustering
// keeps the flux, and a small panel lights the floor below it as the
// irradiance formula says.
#include "lights/emitter_lights.hpp"
#include "test_util.hpp"

#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <numbers>

namespace tsr::vk {
namespace {

using test::device;

constexpr float kPi = std::numbers::pi_v<float>;

TEST(VulkanEmitters, AQuadGivesFourPatchesWithItsAreaFacingItsFront) {
  const MeshData q = test::quad({-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1});  // faces +Y
  const auto patches = meshEmitterPatches(q.positions, q.indices);
  ASSERT_EQ(patches.size(), 4u);
  float area = 0.0f;
  glm::vec3 vectorArea(0.0f);
  for (const auto& p : patches) {
    area += p.area;
    vectorArea += p.vectorArea;
    EXPECT_NEAR(p.area, 1.0f, 1e-4f) << "the quarters of a 2 x 2 quad";
    EXPECT_NEAR(std::abs(p.centre.x), 0.5f, 1e-4f);
    EXPECT_NEAR(std::abs(p.centre.z), 0.5f, 1e-4f);
  }
  EXPECT_NEAR(area, 4.0f, 1e-4f);
  EXPECT_LT(glm::length(vectorArea - glm::vec3(0, 4, 0)), 1e-4f);
}

TEST(VulkanEmitters, AClosedMeshHasNoPreferredDirection) {
  const MeshData sphere = test::uvSphere(16, 32);
  const auto patches = meshEmitterPatches(sphere.positions, sphere.indices);
  EXPECT_EQ(patches.size(), 8u) << "one patch an octant";
  glm::vec3 vectorArea(0.0f);
  float area = 0.0f;
  for (const auto& p : patches) {
    vectorArea += p.vectorArea;
    area += p.area;
  }
  EXPECT_NEAR(area, 4.0f * kPi, 0.2f) << "the polyhedron is a little smaller than the sphere";
  EXPECT_LT(glm::length(vectorArea), 1e-3f * area);
}

TEST(VulkanEmitters, ClusteringKeepsAreaAndFluxWithinTheBudget) {
  std::vector<EmitterLight> lights;
  for (int i = 0; i < 100; ++i) {
    EmitterLight l;
    l.position = glm::vec3(float(i % 10), float(i / 10), 0.0f);
    l.radiance = glm::vec3(float(1 + i % 3));
    l.area = 0.5f;
    l.directionalArea = 0.5f;
    l.normal = glm::vec3(0, 0, 1);
    lights.push_back(l);
  }
  glm::vec3 flux(0.0f);
  for (const auto& l : lights) flux += l.power();
  const auto merged = clusterEmitters(lights, 10);
  ASSERT_LE(merged.size(), 10u);
  ASSERT_GE(merged.size(), 2u);
  glm::vec3 mergedFlux(0.0f);
  float area = 0.0f;
  for (const auto& l : merged) {
    mergedFlux += l.power();
    area += l.area;
    EXPECT_NEAR(l.directionalArea, l.area, 1e-3f) << "all face the same way";
  }
  EXPECT_NEAR(area, 50.0f, 1e-3f);
  EXPECT_LT(glm::length(mergedFlux - flux), 1e-3f * glm::length(flux));
  EXPECT_TRUE(clusterEmitters(lights, 0).empty());
}

// A 0.2 x 0.2 panel of radiance 100, 2 units above a floor of albedo 0.5:
// below it the floor receives E = L A cos / (d^2 + A / pi) from each of the
// panel's patches (within 1 % of the exact square's irradiance here), and
// shows 0.5 / pi x E.
TEST(VulkanEmitters, APanelLightsTheFloorBelowIt) {
  Scene scene(device());
  Material floor;
  floor.baseColor = glm::vec3(0.5f);
  Material panel;
  panel.emission = glm::vec3(100.0f);
  scene.addInstance(scene.addMesh(test::groundQuad(0, 0, 3)), scene.addMaterial(floor), glm::mat4(1.0f));
  // Facing down: the reversed ground quad's winding.
  scene.addInstance(scene.addMesh(test::quad({-0.1f, 2, -0.1f}, {0.1f, 2, -0.1f}, {0.1f, 2, 0.1f}, {-0.1f, 2, 0.1f})),
                    scene.addMaterial(panel), glm::mat4(1.0f));
  const Camera cam = Camera::lookAt({0, 1.5f, 3}, {0, 0, 0}, {0, 1, 0}, 0.9f, 1.0f);
  const Region full = Region::full(64, 64);
  const glm::vec2 centre = test::project(cam, full, {0, 0, 0});
  const auto px = std::uint32_t(centre.x), py = std::uint32_t(centre.y);
  const glm::vec3 seen = test::pixelOnPlane(cam, full, int(px), int(py), {0, 1, 0}, 0.0f);

  const float area = 0.04f, quarter = area / 4.0f;
  float irradiance = 0.0f;
  for (float x : {-0.05f, 0.05f})
    for (float z : {-0.05f, 0.05f}) {
      const glm::vec3 d = glm::vec3(x, 2, z) - seen;
      const float d2 = glm::dot(d, d), c = d.y / std::sqrt(d2);
      irradiance += 100.0f * quarter * c * c / (d2 + quarter / kPi);
    }
  const float expected = 0.5f / kPi * irradiance;

  FrameBuffer fb(64, 64);
  Renderer renderer(device(), {.msaaSamples = 1, .emitterAmbient = false});
  renderer.render(scene, cam, full, fb);
  EXPECT_NEAR(fb.colour(px, py).r, expected, 0.01f * expected);
  EXPECT_GT(renderer.lastStats().shadowMaps, 0u) << "a flat panel casts shadows";

  renderer.setSettings({.msaaSamples = 1, .emitterLights = 0, .emitterAmbient = false});
  renderer.render(scene, cam, full, fb);
  EXPECT_EQ(fb.colour(px, py).r, 0.0f) << "without emitter lights it only glows";

  // The ambient estimate adds light where the panel does not shine directly.
  renderer.setSettings({.msaaSamples = 1, .emitterLights = 32, .emitterAmbient = true});
  renderer.render(scene, cam, full, fb);
  EXPECT_GT(fb.colour(px, py).r, expected);
}

}  // namespace
}  // namespace tsr::vk
