#include "test_scenes.hpp"

#include <gtest/gtest.h>

namespace tsr::embree::test {
namespace {

TEST(EmbreeTexture, BilinearWrapsAndDecodesSrgb) {
  std::vector<std::uint8_t> rgba = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 128, 128, 128, 128};
  Texture t = Texture::fromRgba8(2, 2, rgba);
  EXPECT_EQ(t.sampleBilinear({0.25f, 0.25f}), glm::vec4(1, 0, 0, 1));
  EXPECT_NEAR(t.texel(1, 1).x, 0.2158f, 1e-3f);       // sRGB 128
  EXPECT_NEAR(t.texel(1, 1).w, 128.0f / 255, 1e-6f);  // alpha stays linear
  // Half-way between texel 1 of row 0 and texel 0 (wrapped) of row 0.
  glm::vec4 edge = t.sampleBilinear({1.0f, 0.25f});
  EXPECT_NEAR(edge.x, 0.5f, 1e-5f);
  EXPECT_NEAR(edge.y, 0.5f, 1e-5f);
  EXPECT_EQ(t.sampleBilinear({2.25f, -0.75f}), t.sampleBilinear({0.25f, 0.25f}));
}

// A textured quad filling the view: the albedo output shows the texture.
TEST(EmbreeTexture, MeshUvsSelectTexels) {
  Scene scene(sharedDevice());
  const glm::vec4 a(0.9f, 0.1f, 0.1f, 1), b(0.1f, 0.2f, 0.8f, 1);
  std::vector<glm::vec4> texels(64);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) texels[y * 8 + x] = ((x / 4) + (y / 4)) % 2 ? b : a;
  Material m;
  m.baseColor = glm::vec3(1.0f);
  m.baseColorTexture = scene.addTexture(Texture(8, 8, texels));
  // Quad facing +z, uv (0,0) at the top-left corner as seen by the camera.
  scene.addInstance(scene.addMesh(quad({-1, 1, 0}, {1, 1, 0}, {1, -1, 0}, {-1, -1, 0})), scene.addMaterial(m),
                    glm::mat4(1.0f));
  scene.setEnvironment(Environment::constant(glm::vec3(1.0f)));
  Camera camera;
  camera.cameraToWorld = glm::mat4(1.0f);
  camera.cameraToWorld[3] = glm::vec4(0, 0, 2, 1);
  camera.left = camera.bottom = -0.5f;
  camera.right = camera.top = 0.5f;
  Renderer renderer;
  FrameBuffer fb(16, 16);
  render(renderer, scene, camera, Region::full(16, 16), fb, 2);
  // Block interiors (pixels 1..6 and 9..14) are pure texels.
  EXPECT_NEAR(fb.albedo(3, 3).x, a.x, 1e-5f);
  EXPECT_NEAR(fb.albedo(12, 3).z, b.z, 1e-5f);
  EXPECT_NEAR(fb.albedo(3, 12).z, b.z, 1e-5f);
  EXPECT_NEAR(fb.albedo(12, 12).x, a.x, 1e-5f);
  EXPECT_GT(fb.colour(3, 3).x, fb.colour(3, 3).z);
  EXPECT_GT(fb.colour(12, 3).z, fb.colour(12, 3).x);
}

}  // namespace
}  // namespace tsr::embree::test
