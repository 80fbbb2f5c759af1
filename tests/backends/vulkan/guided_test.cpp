// Guided visibility (two-phase occlusion culling) against the full draw: a
// wall hides a row of spheres; the images must match bit for bit while the
// guided renderer draws fewer objects.
#include "test_util.hpp"

#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

namespace tsr::vk {
namespace {

using test::device;

constexpr std::uint32_t kSize = 96;
const Camera kCam = Camera::lookAt({0, 1.5f, 5}, {0, 0, 0}, {0, 1, 0}, 0.8f, 1.0f);

glm::mat4 at(glm::vec3 p) { return glm::translate(glm::mat4(1.0f), p); }

struct WallScene {
  Scene scene{device()};
  std::vector<InstanceId> hidden;
  InstanceId visible{};
  MeshId sphere{};

  WallScene() {
    sphere = scene.addMesh(test::uvSphere(10, 14, 0.25f));
    const MeshId wall =
        scene.addMesh(test::quad({-1.4f, -0.6f, 1}, {1.4f, -0.6f, 1}, {1.4f, 2.2f, 1}, {-1.4f, 2.2f, 1}));
    const MeshId ground = scene.addMesh(test::groundQuad(0, 0, 4, -0.6f));
    Material red, grey;
    red.baseColor = {0.8f, 0.2f, 0.1f};
    grey.baseColor = {0.5f, 0.5f, 0.5f};
    const MaterialId redId = scene.addMaterial(red), greyId = scene.addMaterial(grey);
    scene.addInstance(wall, greyId, glm::mat4(1.0f));
    scene.addInstance(ground, greyId, glm::mat4(1.0f));
    for (int i = 0; i < 5; ++i) hidden.push_back(scene.addInstance(sphere, redId, at({-0.8f + 0.4f * i, 0, -1})));
    visible = scene.addInstance(sphere, redId, at({1.9f, 0, 0}));
    scene.addLight(DirectionalLight{{0.2f, -1, -0.4f}, glm::vec3(2.0f)});
  }
};

struct Pair {
  Renderer full{device()};
  Renderer guided{device(), [] {
                    RenderSettings s;
                    s.visibility = Visibility::Guided;
                    return s;
                  }()};
  FrameBuffer a{kSize, kSize}, b{kSize, kSize};

  // Renders both; true when colour and depth are identical.
  bool same(Scene& scene, const Camera& camera = kCam) {
    full.render(scene, camera, Region::full(kSize, kSize), a);
    guided.render(scene, camera, Region::full(kSize, kSize), b);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a.colourImage().size(); ++i)
      differ += a.colourImage()[i] != b.colourImage()[i] || a.depthImage()[i] != b.depthImage()[i];
    if (differ) std::printf("%zu pixels differ (guided drew %u objects)\n", differ, guided.lastStats().objects);
    return differ == 0;
  }
};

TEST(VulkanGuided, EqualsFullDrawAndSkipsHiddenObjects) {
  WallScene w;
  Pair p;
  EXPECT_TRUE(p.same(w.scene));  // first frame: everything is tested late, against nothing
  EXPECT_EQ(p.guided.lastStats().objects, p.full.lastStats().objects);
  EXPECT_EQ(p.guided.lastStats().lateObjects, 8u);
  EXPECT_TRUE(p.same(w.scene));  // the finished first frame's depth already showed the wall
  EXPECT_EQ(p.full.lastStats().objects, 8u);
  EXPECT_EQ(p.guided.lastStats().objects, 3u) << "wall, ground and the visible sphere";
  EXPECT_EQ(p.guided.lastStats().lateObjects, 0u);
  EXPECT_LT(p.guided.lastStats().triangles, p.full.lastStats().triangles);
}

TEST(VulkanGuided, ObjectMovingOutFromBehindTheWallAppearsThatFrame) {
  WallScene w;
  Pair p;
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(p.same(w.scene));
  ASSERT_EQ(p.guided.lastStats().objects, 3u);
  const FrameBuffer before = p.b;
  w.scene.setInstanceTransform(w.hidden[0], at({-1.9f, 0, 0}));
  EXPECT_TRUE(p.same(w.scene));
  EXPECT_GT(test::maxAbsDiff(before, p.b), 0.1f) << "the sphere shows beside the wall";
  EXPECT_EQ(p.guided.lastStats().lateObjects, 1u);
  EXPECT_TRUE(p.same(w.scene));
}

TEST(VulkanGuided, MovedVisibleObjectIsDrawnWhereItMovedTo) {
  WallScene w;
  Pair p;
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(p.same(w.scene));
  // Drawn early (it was visible), at its new place, the same frame.
  w.scene.setInstanceTransform(w.visible, at({1.9f, 1.2f, 0}));
  EXPECT_TRUE(p.same(w.scene));
  EXPECT_EQ(p.guided.lastStats().lateObjects, 0u);
  // Moved behind the wall: gone the same frame, and no longer drawn after.
  w.scene.setInstanceTransform(w.visible, at({0, 0, -2}));
  EXPECT_TRUE(p.same(w.scene));
  EXPECT_TRUE(p.same(w.scene));
  EXPECT_EQ(p.guided.lastStats().objects, 2u);
}

TEST(VulkanGuided, EqualsFullDrawFromSeveralViewsWithMsaaAndRegions) {
  WallScene w;
  for (std::uint32_t samples : {1u, 4u}) {
    Pair p;
    RenderSettings s;
    s.msaaSamples = samples;
    p.full.setSettings(s);
    s.visibility = Visibility::Guided;
    p.guided.setSettings(s);
    for (const glm::vec3 eye :
         {glm::vec3(0, 1.5f, 5), glm::vec3(3, 2, 3), glm::vec3(0, 4, -4), glm::vec3(-2, 0, 1.5f)}) {
      const Camera cam = Camera::lookAt(eye, {0, 0, 0}, {0, 1, 0}, 0.8f, 1.0f);
      EXPECT_TRUE(p.same(w.scene, cam)) << "first frame from " << eye.x << "," << eye.y << "," << eye.z;
      EXPECT_TRUE(p.same(w.scene, cam)) << "second frame from " << eye.x << "," << eye.y << "," << eye.z;
    }
  }
  // A wall tile: the off-axis sub-frustum culls against its own pyramid.
  Pair p;
  const Region tile{2 * kSize, 2 * kSize, kSize / 2, kSize / 2, kSize / 2 + kSize, kSize / 2 + kSize};
  p.full.render(w.scene, kCam, tile, p.a);
  for (int i = 0; i < 2; ++i) p.guided.render(w.scene, kCam, tile, p.b);
  EXPECT_EQ(p.a.colourImage(), p.b.colourImage());
}

}  // namespace
}  // namespace tsr::vk
