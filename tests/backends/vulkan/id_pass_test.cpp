// The id pass: object ids of the nearest opaque instance through pixel
// centres, transparent instances left out, depth like the colour pass.
#include "test_util.hpp"

#include "tsr/vk/error.hpp"
#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

namespace tsr::vk {
namespace {

using test::device;

// Looking down -Z from z = 5 at a wall (z = 0) and a smaller quad in front (z = 1).
const Camera kCam = Camera::lookAt({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 0.8f, 1.0f);

struct Rig {
  Scene scene{device()};
  MaterialId opaque = scene.addMaterial({});
  InstanceId wall, front;
  Rig() {
    MeshId quad = scene.addMesh(test::quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}));
    wall = scene.addInstance(quad, opaque, glm::scale(glm::mat4(1.0f), glm::vec3(1.5f)));
    front = scene.addInstance(
        quad, opaque, glm::translate(glm::mat4(1.0f), {0, 0, 1}) * glm::scale(glm::mat4(1.0f), glm::vec3(0.4f)));
    scene.setInstanceObject(wall, 7);
    scene.setInstanceObject(front, 42);
  }
  IdBuffer ids() {
    Renderer renderer(device());
    IdBuffer out(32, 32);
    renderer.renderIds(scene, kCam, Region::full(32, 32), out);
    return out;
  }
};

TEST(VulkanIdPass, NearestOpaqueObjectAndItsDepth) {
  Rig rig;
  IdBuffer ids = rig.ids();
  EXPECT_EQ(ids.ids[ids.index(16, 16)], 42u);
  EXPECT_NEAR(ids.depth[ids.index(16, 16)], 4.0f, 1e-3f);
  EXPECT_EQ(ids.ids[ids.index(16, 8)], 7u);
  EXPECT_NEAR(ids.depth[ids.index(16, 8)], 5.0f, 1e-3f);
  EXPECT_EQ(ids.ids[ids.index(0, 0)], kNoObject) << "the wall does not reach the corner";
  EXPECT_EQ(ids.depth[ids.index(0, 0)], std::numeric_limits<float>::infinity());
}

TEST(VulkanIdPass, TransparentInstancesNeitherOccludeNorCount) {
  Rig rig;
  Material glass;
  glass.opacity = 0.5f;
  rig.scene.setInstanceMaterial(rig.front, rig.scene.addMaterial(glass));
  IdBuffer ids = rig.ids();
  EXPECT_EQ(ids.ids[ids.index(16, 16)], 7u) << "the wall behind shows through";
  for (auto id : ids.ids) EXPECT_NE(id, 42u);
}

TEST(VulkanIdPass, DefaultObjectIsTheInstanceIndexPlusOne) {
  Scene scene(device());
  MeshId quad = scene.addMesh(test::quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}));
  InstanceId a = scene.addInstance(quad, scene.addMaterial({}), glm::mat4(1.0f));
  EXPECT_EQ(scene.instanceObject(a), index(a) + 1);
  scene.setInstanceObject(a, 99);
  EXPECT_EQ(scene.instanceObject(a), 99u);
  Renderer renderer(device());
  IdBuffer wrong(8, 8);
  EXPECT_THROW(renderer.renderIds(scene, kCam, Region::full(16, 16), wrong), Error);
}

TEST(VulkanIdPass, RegionsAreCrops) {
  Rig rig;
  IdBuffer whole = rig.ids();
  Renderer renderer(device());
  Region region{32, 32, 5, 9, 27, 20};
  IdBuffer tile(region.regionWidth(), region.regionHeight());
  renderer.renderIds(rig.scene, kCam, region, tile);
  std::size_t same = 0;
  for (std::uint32_t y = 0; y < tile.height; ++y)
    for (std::uint32_t x = 0; x < tile.width; ++x)
      same += tile.ids[tile.index(x, y)] == whole.ids[whole.index(x + region.x0, y + region.y0)];
  EXPECT_GE(same, tile.ids.size() - tile.height) << "edges may round differently";
}

}  // namespace
}  // namespace tsr::vk
