// The reflection probe: mirrors show the room around them, and the probe is
// drawn again only when the scene changed.
#include "test_util.hpp"

#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"

#include <gtest/gtest.h>

namespace tsr::vk {
namespace {

using test::device;

Material glowing(glm::vec3 e) {
  Material m;
  m.baseColor = glm::vec3(0.0f);
  m.emission = e;
  return m;
}

// A room [-2, 2]^3 open towards +z: red wall at x = -2, green at x = +2,
// blue at the back, grey floor and ceiling; a mirror sphere off the centre.
struct Room {
  Scene scene{device()};
  MaterialId red, green;
  Room() {
    red = scene.addMaterial(glowing({1, 0, 0}));
    green = scene.addMaterial(glowing({0, 1, 0}));
    const MaterialId blue = scene.addMaterial(glowing({0, 0, 1})), grey = scene.addMaterial(glowing(glm::vec3(0.3f)));
    auto wall = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, MaterialId m) {
      scene.addInstance(scene.addMesh(test::quad(a, b, c, d)), m, glm::mat4(1.0f));
    };
    wall({-2, -2, 2}, {-2, -2, -2}, {-2, 2, -2}, {-2, 2, 2}, red);   // faces +x
    wall({2, -2, -2}, {2, -2, 2}, {2, 2, 2}, {2, 2, -2}, green);     // faces -x
    wall({-2, -2, -2}, {2, -2, -2}, {2, 2, -2}, {-2, 2, -2}, blue);  // faces +z
    wall({-2, -2, 2}, {2, -2, 2}, {2, -2, -2}, {-2, -2, -2}, grey);  // floor, faces +y
    wall({-2, 2, -2}, {2, 2, -2}, {2, 2, 2}, {-2, 2, 2}, grey);      // ceiling, faces -y
    Material mirror;
    mirror.type = MaterialType::Mirror;
    mirror.baseColor = glm::vec3(1.0f);
    scene.addInstance(scene.addMesh(test::uvSphere(32, 64, 0.5f)), scene.addMaterial(mirror),
                      glm::translate(glm::mat4(1.0f), {0.8f, 0.0f, 0.0f}));
  }
};

TEST(VulkanReflectionProbe, MirrorShowsTheWallItFaces) {
  Room room;
  const Camera cam = Camera::lookAt({0.8f, 0, 1.8f}, {0.8f, 0, 0}, {0, 1, 0}, 0.9f, 1.0f);
  const Region full = Region::full(96, 96);
  Renderer renderer(device(), {.emitterLights = 0, .emitterAmbient = false});
  FrameBuffer fb(96, 96);
  renderer.render(room.scene, cam, full, fb);
  test::writePng("/tmp/tsr_vk_probe_mirror.png", fb);
  EXPECT_EQ(renderer.lastStats().probes, 1u);
  // Normals 45 degrees to the left and right: mirrored towards -x and +x.
  const glm::vec2 left = test::project(cam, full, {0.8f - 0.354f, 0, 0.354f});
  const glm::vec2 right = test::project(cam, full, {0.8f + 0.354f, 0, 0.354f});
  const glm::vec4 l = fb.colour(int(left.x), int(left.y)), r = fb.colour(int(right.x), int(right.y));
  EXPECT_GT(l.r, 0.8f) << "the red wall";
  EXPECT_LT(std::max(l.g, l.b), 0.1f);
  EXPECT_GT(r.g, 0.8f) << "the green wall";
  EXPECT_LT(std::max(r.r, r.b), 0.1f);
  // Straight back along the view: the open side, black.
  const glm::vec2 centre = test::project(cam, full, {0.8f, 0, 0.5f});
  EXPECT_LT(fb.colour(int(centre.x), int(centre.y)).g, 0.1f);

  // Unchanged scene: the probe is kept. An edit: drawn again, and it shows.
  renderer.render(room.scene, cam, full, fb);
  EXPECT_EQ(renderer.lastStats().probes, 0u);
  room.scene.setMaterial(room.red, glowing({1, 1, 0}));
  renderer.render(room.scene, cam, full, fb);
  EXPECT_EQ(renderer.lastStats().probes, 1u);
  EXPECT_GT(fb.colour(int(left.x), int(left.y)).g, 0.8f) << "the wall turned yellow";
}

}  // namespace
}  // namespace tsr::vk
