#include "test_util.hpp"

#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"

#include <gtest/gtest.h>

namespace tsr::vk {
namespace {

// Renders a scene that uses every feature (textures, transparency, spot and
// directional shadows, point light, ambient, MSAA on and off, regions, edits
// between frames) on a device with VK_LAYER_KHRONOS_validation and expects
// the debug messenger to have seen no error and no warning.
TEST(VulkanValidation, EveryFeatureRendersWithoutValidationMessages) {
  if (!Device::validationLayerAvailable()) GTEST_SKIP() << "VK_LAYER_KHRONOS_validation not installed";
  std::shared_ptr<Device> device = Device::create({.validation = true});
  {
    Scene scene(device);
    std::vector<std::uint8_t> texels(8 * 8 * 4);
    for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = std::uint8_t((i * 37) & 0xff);
    TextureId tex = scene.addTexture(Texture::fromRgba8(8, 8, texels));
    std::vector<glm::vec4> hdr(4 * 4, glm::vec4(2.0f, 1.0f, 0.5f, 1.0f));
    TextureId glowTex = scene.addTexture(Texture::fromFloat(4, 4, hdr));

    Material textured;
    textured.baseColorTexture = tex;
    Material glass;
    glass.type = MaterialType::Dielectric;
    glass.opacity = 0.4f;
    glass.baseColor = {0.2f, 0.5f, 0.9f};
    Material glow;
    glow.emission = glm::vec3(1.0f);
    glow.emissionTexture = glowTex;
    Material metal;
    metal.type = MaterialType::Conductor;
    MaterialId texturedId = scene.addMaterial(textured);
    MaterialId glassId = scene.addMaterial(glass);
    MaterialId glowId = scene.addMaterial(glow);
    MaterialId metalId = scene.addMaterial(metal);

    MeshId sphere = scene.addMesh(test::uvSphere(10, 14, 0.5f));
    const MeshData groundMesh = test::groundQuad(0, 0, 3, -0.5f);
    MeshId ground = scene.addMesh(groundMesh);
    MeshId flat = scene.addMesh(test::quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, false));
    scene.addInstance(ground, texturedId, glm::mat4(1.0f));
    InstanceId moving = scene.addInstance(sphere, metalId, glm::translate(glm::mat4(1.0f), {-0.8f, 0, 0}));
    scene.addInstance(sphere, glowId, glm::translate(glm::mat4(1.0f), {0.8f, 0, 0}));
    scene.addInstance(flat, glassId, glm::translate(glm::mat4(1.0f), {0, 0, 1.0f}));
    scene.addLight(PointLight{{0, 2, 2}, glm::vec3(10.0f)});
    scene.addLight(DirectionalLight{{0.3f, -1, -0.2f}, glm::vec3(1.0f)});
    SpotLight spot;
    spot.position = {1, 3, 1};
    spot.direction = {-0.3f, -1, -0.3f};
    spot.intensity = glm::vec3(15.0f);
    scene.addLight(spot);
    scene.setEnvironment(Environment::constant(glm::vec3(0.05f)));

    const Camera cam = Camera::lookAt({0, 1.5f, 4}, {0, 0, 0}, {0, 1, 0}, 0.9f, 1.5f);
    Renderer renderer(device, {.msaaSamples = 4, .shadows = true, .shadowMapSize = 256});
    FrameBuffer full(96, 64);
    renderer.render(scene, cam, Region::full(96, 64), full);
    test::writePng("/tmp/tsr_vk_every_feature.png", full);
    // Spot and directional light, then the glowing sphere's octant patches
    // (mostly flat, so shadowed) up to the 8 maps a frame has.
    EXPECT_EQ(renderer.lastStats().shadowMaps, 8u);

    scene.setInstanceTransform(moving, glm::translate(glm::mat4(1.0f), {-0.8f, 0.3f, 0}));
    std::vector<glm::vec3> groundPositions = groundMesh.positions;
    groundPositions[0] = {-3, -0.6f, 3};
    scene.updateMeshVertices(ground, {.positions = groundPositions, .count = 1});
    scene.setInstanceMaterial(moving, texturedId);
    scene.removeMaterial(metalId);
    FrameBuffer part(40, 30);
    renderer.render(scene, cam, Region{96, 64, 10, 20, 50, 50}, part);
    renderer.setSettings({.msaaSamples = 1, .shadows = true, .shadowMapSize = 128});
    renderer.render(scene, cam, Region::full(96, 64), full);
  }
  for (const std::string& m : device->validationMessages()) ADD_FAILURE() << m;
  EXPECT_EQ(device->validationErrors(), 0u);
  EXPECT_EQ(device->validationWarnings(), 0u);
}

// The look of issue 27 and 28 under the validation layer: a see-through
// volume, fog, the metallic-roughness BRDF with its textures and a normal
// map, a prefiltered environment map and the reflection probe (a mirror and
// glass), with and without MSAA and guided visibility, and an edit that
// redraws the probe.
TEST(VulkanValidation, MediaMaterialsAndProbeRenderWithoutValidationMessages) {
  if (!Device::validationLayerAvailable()) GTEST_SKIP() << "VK_LAYER_KHRONOS_validation not installed";
  std::shared_ptr<Device> device = Device::create({.validation = true});
  {
    Scene scene(device);
    std::vector<std::uint8_t> texels(8 * 8 * 4);
    for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = std::uint8_t((i * 53) & 0xff);
    const TextureId tex = scene.addTexture(Texture::fromRgba8(8, 8, texels, false));
    Material gltf;
    gltf.type = MaterialType::MetallicRoughness;
    gltf.metallic = 0.7f;
    gltf.metallicRoughnessTexture = tex;
    gltf.normalTexture = tex;
    Material mirror;
    mirror.type = MaterialType::Mirror;
    Material glass;
    glass.type = MaterialType::Glass;
    Material medium;
    medium.type = MaterialType::Glass;
    medium.ior = 1.0f;
    medium.interior = Medium{glm::vec3(0.5f), glm::vec3(0.8f), glm::vec3(0.1f), 0.3f};
    const MeshId sphere = scene.addMesh(test::uvSphere(10, 14, 0.4f));
    const MeshId ground = scene.addMesh(test::groundQuad(0, 0, 3, -0.5f));
    scene.addInstance(ground, scene.addMaterial(gltf), glm::mat4(1.0f));
    const MaterialId mirrorId = scene.addMaterial(mirror);
    scene.addInstance(sphere, mirrorId, glm::translate(glm::mat4(1.0f), {-1.2f, 0, 0}));
    scene.addInstance(sphere, scene.addMaterial(glass), glm::translate(glm::mat4(1.0f), {1.2f, 0, 0}));
    scene.addInstance(sphere, scene.addMaterial(medium), glm::translate(glm::mat4(1.0f), {0, 0, 0.8f}));
    SpotLight spot;
    spot.position = {1, 3, 1};
    spot.direction = {-0.3f, -1, -0.3f};
    spot.intensity = glm::vec3(15.0f);
    scene.addLight(spot);
    std::vector<glm::vec4> sky(16 * 8);
    for (std::size_t i = 0; i < sky.size(); ++i) sky[i] = glm::vec4(float(i % 5) * 0.1f, 0.2f, 0.3f, 1.0f);
    scene.setEnvironment(Environment::latLong(16, 8, sky).withFog(Medium{glm::vec3(0.02f), glm::vec3(0.05f), {}, 0}));

    const Camera cam = Camera::lookAt({0, 1.5f, 4}, {0, 0, 0}, {0, 1, 0}, 0.9f, 1.5f);
    FrameBuffer full(96, 64);
    for (std::uint32_t samples : {4u, 1u})
      for (Visibility visibility : {Visibility::All}) {
        Renderer renderer(device, {.msaaSamples = samples, .visibility = visibility, .shadowMapSize = 256});
        renderer.render(scene, cam, Region::full(96, 64), full);
        EXPECT_EQ(renderer.lastStats().probes, 1u);
        mirror.baseColor = glm::vec3(0.5f + 0.1f * float(samples));
        scene.setMaterial(mirrorId, mirror);
        renderer.render(scene, cam, Region::full(96, 64), full);
        EXPECT_EQ(renderer.lastStats().probes, 1u);
      }
    test::writePng("/tmp/tsr_vk_look_features.png", full);
  }
  for (const std::string& m : device->validationMessages()) ADD_FAILURE() << m;
  EXPECT_EQ(device->validationErrors(), 0u);
  EXPECT_EQ(device->validationWarnings(), 0u);
}

}  // namespace
}  // namespace tsr::vk
