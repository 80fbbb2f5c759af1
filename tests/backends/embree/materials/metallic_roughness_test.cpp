// Properties of the glTF metallic-roughness BSDF seen in real renders
// (its estimators' agreement is in area_light_test.cpp, its energy in
// furnace_test.cpp): roughness widens a highlight, a mirror shows the wall it faces, a normal
// map changes shading where it is tilted and nowhere else.
#include "test_scenes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace tsr::embree::test {
namespace {

Material gltf(const glm::vec3& colour, float metallic, float roughness) {
  Material m;
  m.type = MaterialType::MetallicRoughness;
  m.baseColor = colour;
  m.metallic = metallic;
  m.roughness = roughness;
  return m;
}

Material lamp(const glm::vec3& emission) {
  Material m;
  m.baseColor = glm::vec3(0.0f);
  m.emission = emission;
  return m;
}

// A white metal sphere under a small lamp, nothing else: the highlight's
// spread (luminance-weighted mean distance from its brightest pixel, in
// pixels) grows with roughness.
float highlightSpread(float roughness) {
  Scene scene(sharedDevice());
  scene.addInstance(scene.addMesh(uvSphere({0, 0, 0}, 1.0f, 8000, true)),
                    scene.addMaterial(gltf(glm::vec3(1.0f), 1.0f, roughness)), glm::mat4(1.0f));
  scene.addInstance(scene.addMesh(quad({-0.3f, 3, 2.7f}, {0.3f, 3, 2.7f}, {0.3f, 3, 3.3f}, {-0.3f, 3, 3.3f})),
                    scene.addMaterial(lamp(glm::vec3(50.0f))), glm::mat4(1.0f));
  RenderSettings s;
  s.samplesPerPass = 8;
  Renderer renderer(s);
  Camera camera = Camera::lookAt({0, 0, 4}, {0, 0, 0}, {0, 1, 0}, glm::radians(35.0f), 1.0f);
  const std::uint32_t n = 48;
  FrameBuffer fb(n, n);
  render(renderer, scene, camera, Region::full(n, n), fb, 8);
  std::uint32_t px = 0, py = 0;
  float peak = -1.0f;
  for (std::uint32_t y = 0; y < n; ++y)
    for (std::uint32_t x = 0; x < n; ++x)
      if (float l = luminance(glm::vec3(fb.colour(x, y))); l > peak) peak = l, px = x, py = y;
  double sum = 0.0, weighted = 0.0;
  for (std::uint32_t y = 0; y < n; ++y)
    for (std::uint32_t x = 0; x < n; ++x) {
      const float l = luminance(glm::vec3(fb.colour(x, y)));
      sum += l;
      weighted += l * std::hypot(float(x) - float(px), float(y) - float(py));
    }
  return sum > 0.0 ? float(weighted / sum) : 0.0f;
}

TEST(EmbreeMetallicRoughness, RoughnessWidensHighlightMonotonically) {
  float last = -1.0f;
  for (float roughness : {0.0f, 0.25f, 0.5f, 1.0f}) {
    const float spread = highlightSpread(roughness);
    EXPECT_GT(spread, last * 1.1f) << "roughness " << roughness;
    last = spread;
  }
}

// A smooth metal sphere between a red wall on its left and a green one on
// its right (both emissive, nothing else lit): each side shows its wall.
TEST(EmbreeMetallicRoughness, MirrorSphereShowsTheWallItFaces) {
  Scene scene(sharedDevice());
  scene.addInstance(scene.addMesh(uvSphere({0, 0, 0}, 1.0f, 8000, true)),
                    scene.addMaterial(gltf(glm::vec3(0.9f), 1.0f, 0.0f)), glm::mat4(1.0f));
  scene.addInstance(scene.addMesh(quad({-3, -3, 3}, {-3, -3, -3}, {-3, 3, -3}, {-3, 3, 3})),
                    scene.addMaterial(lamp({1, 0, 0})), glm::mat4(1.0f));
  scene.addInstance(scene.addMesh(quad({3, -3, -3}, {3, -3, 3}, {3, 3, 3}, {3, 3, -3})),
                    scene.addMaterial(lamp({0, 1, 0})), glm::mat4(1.0f));
  Renderer renderer;
  Camera camera = Camera::lookAt({0, 0, 4}, {0, 0, 0}, {0, 1, 0}, glm::radians(35.0f), 1.0f);
  FrameBuffer fb(32, 32);
  render(renderer, scene, camera, Region::full(32, 32), fb, 2);
  glm::vec3 left(0.0f), right(0.0f);
  for (std::uint32_t y = 12; y < 20; ++y)
    for (std::uint32_t x = 6; x < 11; ++x) {
      left += glm::vec3(fb.colour(x, y));
      right += glm::vec3(fb.colour(31 - x, y));
    }
  EXPECT_GT(left.x, 0.1f);
  EXPECT_GT(right.y, 0.1f);
  EXPECT_GT(left.x, 10.0f * left.y);
  EXPECT_GT(right.y, 10.0f * right.x);
}

// A quad under a slanting directional light; the left half of its normal
// map is flat, the right half tilts the normal towards the light.
FrameBuffer normalMapped(bool withMap) {
  Scene scene(sharedDevice());
  Material m = gltf(glm::vec3(0.7f), 0.0f, 0.5f);
  if (withMap) {
    std::vector<glm::vec4> texels(64);
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x)
        texels[y * 8 + x] = x < 4 ? glm::vec4(0.5f, 0.5f, 1.0f, 1.0f) : glm::vec4(0.8f, 0.5f, 0.9f, 1.0f);
    m.normalTexture = scene.addTexture(Texture(8, 8, texels));
  }
  // Facing the camera, u along +x: the left half of the view is uv.x < 0.5.
  scene.addInstance(scene.addMesh(quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0})), scene.addMaterial(m),
                    glm::mat4(1.0f));
  scene.addLight(DirectionalLight{glm::normalize(glm::vec3(-1.0f, 0.0f, -1.0f)), glm::vec3(2.0f)});
  Camera camera;
  camera.cameraToWorld = glm::mat4(1.0f);
  camera.cameraToWorld[3] = glm::vec4(0, 0, 2, 1);
  camera.left = camera.bottom = -0.5f;
  camera.right = camera.top = 0.5f;
  Renderer renderer;
  FrameBuffer fb(16, 16);
  render(renderer, scene, camera, Region::full(16, 16), fb, 2);
  return fb;
}

TEST(EmbreeMetallicRoughness, NormalMapChangesShadingOnlyWhereTilted) {
  const FrameBuffer flat = normalMapped(false), mapped = normalMapped(true);
  float tilted = 0.0f, plain = 0.0f;
  for (std::uint32_t y = 0; y < 16; ++y) {
    for (std::uint32_t x = 2; x < 7; ++x)  // uv.x in (0.125, 0.4375): flat texels only
      EXPECT_NEAR(mapped.colour(x, y).x, flat.colour(x, y).x, 1e-4f * flat.colour(x, y).x) << x << "," << y;
    for (std::uint32_t x = 10; x < 14; ++x) {  // tilted texels only
      tilted += mapped.colour(x, y).x;
      plain += flat.colour(x, y).x;
    }
  }
  // Turned towards the light (+x side): brighter by far more than noise.
  EXPECT_GT(plain, 0.0f);
  EXPECT_GT(tilted, 1.3f * plain);
}

}  // namespace
}  // namespace tsr::embree::test
