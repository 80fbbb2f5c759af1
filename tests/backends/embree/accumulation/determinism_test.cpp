#include "test_scenes.hpp"

#include <gtest/gtest.h>

namespace tsr::embree::test {
namespace {

// Every feature at once: textures, glass, mirror, GGX, glTF metallic-roughness, area, point, spot and
// directional lights, environment.
Camera richScene(Scene& scene) {
  Camera camera = cornellBox(scene, 0, 4.0f / 3.0f);
  Material glass;
  glass.type = MaterialType::Glass;
  glass.baseColor = glm::vec3(1.0f);
  scene.addInstance(scene.addMesh(uvSphere({180, 260, 170}, 70, 800, true)), scene.addMaterial(glass), glm::mat4(1.0f));
  Material mirror;
  mirror.type = MaterialType::Mirror;
  scene.addInstance(scene.addMesh(uvSphere({380, 400, 350}, 60, 800, true)), scene.addMaterial(mirror),
                    glm::mat4(1.0f));
  Material lamp;
  lamp.baseColor = glm::vec3(0.0f);
  lamp.emission = glm::vec3(12.0f, 11.0f, 9.0f);
  scene.addInstance(scene.addMesh(quad({213, 548, 227}, {343, 548, 227}, {343, 548, 332}, {213, 548, 332})),
                    scene.addMaterial(lamp), glm::mat4(1.0f));
  std::vector<glm::vec4> texels;
  for (int i = 0; i < 16; ++i)
    texels.push_back((i + i / 4) % 2 ? glm::vec4(0.9f, 0.8f, 0.2f, 1) : glm::vec4(0.2f, 0.3f, 0.9f, 1));
  Material rough;
  rough.type = MaterialType::Conductor;
  rough.roughness = 0.4f;
  rough.baseColorTexture = scene.addTexture(Texture(4, 4, texels));
  scene.addInstance(scene.addMesh(quad({100, 1, 400}, {300, 1, 400}, {300, 1, 500}, {100, 1, 500})),
                    scene.addMaterial(rough), glm::mat4(1.0f));
  // glTF metallic-roughness with every per-hit texture: its lobe choice,
  // multiple-scattering table and normal map must not depend on threads.
  std::vector<glm::vec4> params, normals;
  for (int i = 0; i < 16; ++i) {
    params.push_back(glm::vec4(0, i % 2 ? 0.2f : 0.9f, (i / 4) % 2 ? 1.0f : 0.0f, 1));
    normals.push_back(i % 3 ? glm::vec4(0.5f, 0.5f, 1, 1) : glm::vec4(0.8f, 0.4f, 0.85f, 1));
  }
  Material gltf;
  gltf.type = MaterialType::MetallicRoughness;
  gltf.baseColor = glm::vec3(0.8f, 0.6f, 0.5f);
  gltf.metallic = 1.0f;
  gltf.roughness = 1.0f;
  gltf.transmission = 0.3f;
  gltf.metallicRoughnessTexture = scene.addTexture(Texture(4, 4, params));
  gltf.normalTexture = scene.addTexture(Texture(4, 4, normals));
  scene.addInstance(scene.addMesh(quad({400, 1, 100}, {500, 1, 100}, {500, 1, 250}, {400, 1, 250})),
                    scene.addMaterial(gltf), glm::mat4(1.0f));
  scene.addLight(SpotLight{{400, 500, 100}, {0, -1, 0.3f}, glm::vec3(50000.0f), 0.3f, 0.5f});
  scene.addLight(DirectionalLight{{0.2f, -1.0f, 0.3f}, glm::vec3(0.5f)});
  scene.setEnvironment(Environment::constant(glm::vec3(0.1f, 0.15f, 0.2f)));
  return camera;
}

TEST(EmbreeDeterminism, ThreadCountAndTileSizeDoNotChangeTheImage) {
  Scene scene(sharedDevice());
  Camera camera = richScene(scene);
  Region region = Region::full(40, 30);
  RenderSettings a;
  a.seed = 7;
  a.threads = 1;
  a.tileSize = 7;
  a.samplesPerPass = 2;
  RenderSettings b = a;
  b.threads = 2;
  b.tileSize = 16;
  b.samplesPerPass = 1;
  Renderer ra(a), rb(b);
  FrameBuffer fa(40, 30), fb(40, 30);
  render(ra, scene, camera, region, fa, 2);
  render(rb, scene, camera, region, fb, 4);
  EXPECT_TRUE(identical(fa, fb));
  EXPECT_GT(meanColour(fa).x, 0.0f);

  RenderSettings c = a;
  c.seed = 8;
  Renderer rc(c);
  FrameBuffer fc(40, 30);
  render(rc, scene, camera, region, fc, 2);
  EXPECT_FALSE(identical(fa, fc)) << "a different seed must give a different image";
}

TEST(EmbreeDeterminism, RegionEqualsCropOfFullImage) {
  Scene scene(sharedDevice());
  Camera camera = richScene(scene);
  RenderSettings s;
  s.seed = 3;
  s.tileSize = 5;
  Renderer renderer(s);
  FrameBuffer full(40, 30);
  render(renderer, scene, camera, Region::full(40, 30), full, 3);
  Region crop{40, 30, 7, 5, 29, 23};
  FrameBuffer part(crop.regionWidth(), crop.regionHeight());
  render(renderer, scene, camera, crop, part, 3);
  EXPECT_TRUE(identical(full, part, 7, 5));
}

}  // namespace
}  // namespace tsr::embree::test
