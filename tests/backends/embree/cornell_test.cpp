#include "test_scenes.hpp"

#include <gtest/gtest.h>

namespace tsr::embree::test {
namespace {

// The Cornell box with a glass and a mirror sphere and a ceiling lamp.
// Writes embree_cornell.ppm next to the test binary's working directory to
// look at; the assertions check what must hold regardless of noise.
TEST(EmbreeCornell, WallsHaveTheirColoursAndImageIsWritten) {
  Scene scene(sharedDevice());
  Camera camera = cornellBox(scene, 0);
  Material glass;
  glass.type = MaterialType::Glass;
  glass.baseColor = glm::vec3(1.0f);
  scene.addInstance(scene.addMesh(uvSphere({185, 255, 169}, 75, 3000, true)), scene.addMaterial(glass),
                    glm::mat4(1.0f));
  Material mirror;
  mirror.type = MaterialType::Mirror;
  mirror.baseColor = glm::vec3(0.95f);
  scene.addInstance(scene.addMesh(uvSphere({368, 410, 351}, 80, 3000, true)), scene.addMaterial(mirror),
                    glm::mat4(1.0f));
  Material lamp;
  lamp.baseColor = glm::vec3(0.0f);
  lamp.emission = glm::vec3(15.0f);
  scene.addInstance(scene.addMesh(quad({213, 548, 227}, {343, 548, 227}, {343, 548, 332}, {213, 548, 332})),
                    scene.addMaterial(lamp), glm::mat4(1.0f));
  RenderSettings s;
  s.samplesPerPass = 16;
  Renderer renderer(s);
  FrameBuffer fb(64, 64);
  render(renderer, scene, camera, Region::full(64, 64), fb, 2);
  writePpm("embree_cornell.ppm", fb);

  // Red wall on the left, green on the right (seen from -z looking +z).
  glm::vec4 left = fb.colour(4, 32), right = fb.colour(59, 32);
  EXPECT_GT(left.x, 4.0f * left.y);
  EXPECT_GT(right.y, 4.0f * right.x);
  EXPECT_EQ(left.w, 1.0f);
  // The lamp is the brightest thing seen directly.
  float brightest = 0.0f;
  for (std::uint32_t y = 0; y < 16; ++y) brightest = std::max(brightest, fb.colour(32, y).x);
  EXPECT_NEAR(brightest, 15.0f, 0.01f);
}

}  // namespace
}  // namespace tsr::embree::test
