#include "test_util.hpp"

#include "tsr/vk/error.hpp"
#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace tsr::vk {
namespace {

using test::device;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

TEST(VulkanErrors, BadMeshDataIsRejected) {
  Scene scene(device());
  MeshData m = test::quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0});
  MeshData badIndex = m;
  badIndex.indices[4] = 4;
  EXPECT_THROW(scene.addMesh(badIndex), Error);
  MeshData badCount = m;
  badCount.indices.pop_back();
  EXPECT_THROW(scene.addMesh(badCount), Error);
  MeshData badNormals = m;
  badNormals.normals.pop_back();
  EXPECT_THROW(scene.addMesh(badNormals), Error);
  MeshData nanPos = m;
  nanPos.positions[1].y = kNaN;
  EXPECT_THROW(scene.addMesh(nanPos), Error);
  EXPECT_THROW(scene.addMesh(MeshData{}), Error);
  EXPECT_EQ(scene.meshCount(), 0u);
  EXPECT_EQ(scene.geometryBytesUploaded(), 0u);

  MeshId ok = scene.addMesh(m);
  const std::vector<glm::vec3> four(4, glm::vec3(0.5f));
  EXPECT_THROW(scene.updateMeshVertices(ok, {.positions = four, .first = 3, .count = 2}), Error);  // 3 + 2 > 4 vertices
  EXPECT_THROW(scene.updateMeshVertices(ok, {.positions = std::span(four).first(2), .count = 2}), Error);  // 2 of 4
  EXPECT_THROW(scene.updateMeshVertices(ok, {.positions = four, .normals = std::span(four).first(1), .count = 1}),
               Error);
  EXPECT_THROW(scene.updateMeshVertices(MeshId(99), {.positions = four, .count = 2}), Error);
}

TEST(VulkanErrors, BadInstancesMaterialsAndLightsAreRejected) {
  Scene scene(device());
  MeshId mesh = scene.addMesh(test::quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}));
  MaterialId mat = scene.addMaterial({});
  glm::mat4 nan(1.0f);
  nan[3][1] = kNaN;
  EXPECT_THROW(scene.addInstance(mesh, mat, nan), Error);
  EXPECT_THROW(scene.addInstance(mesh, MaterialId(7), glm::mat4(1.0f)), Error);
  InstanceId inst = scene.addInstance(mesh, mat, glm::mat4(1.0f));
  EXPECT_THROW(scene.setInstanceTransform(inst, nan), Error);
  EXPECT_THROW(scene.removeMesh(mesh), Error);
  EXPECT_THROW(scene.removeMaterial(mat), Error);

  Material bad;
  bad.opacity = 1.5f;
  EXPECT_THROW(scene.addMaterial(bad), Error);
  bad = {};
  bad.baseColorTexture = TextureId(3);
  EXPECT_THROW(scene.addMaterial(bad), Error);
  SpotLight spot;
  spot.innerAngle = 0.5f;
  spot.outerAngle = 0.4f;
  EXPECT_THROW(scene.addLight(spot), Error);
  EXPECT_THROW(scene.addLight(DirectionalLight{{0, 0, 0}, glm::vec3(1.0f)}), Error);
  EXPECT_THROW(scene.addLight(PointLight{{0, 0, 0}, {-1, 0, 0}}), Error);
  EXPECT_THROW(Texture::fromRgba8(2, 2, std::vector<std::uint8_t>(15)), Error);
}

TEST(VulkanErrors, BadRenderInputsAreRejected) {
  Scene scene(device());
  scene.addInstance(scene.addMesh(test::quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0})), scene.addMaterial({}),
                    glm::mat4(1.0f));
  Renderer renderer(device());
  const Camera cam = Camera::lookAt({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 1.0f, 1.0f);
  FrameBuffer fb(8, 8);
  EXPECT_THROW(renderer.render(scene, cam, Region{8, 8, 4, 0, 4, 8}, fb), Error);  // empty
  EXPECT_THROW(renderer.render(scene, cam, Region{0, 0, 0, 0, 0, 0}, fb), Error);  // zero-size image
  EXPECT_THROW(renderer.render(scene, cam, Region{8, 8, 0, 0, 9, 8}, fb), Error);  // outside
  EXPECT_THROW(renderer.render(scene, cam, Region::full(16, 16), fb), Error);      // fb size mismatch
  Camera badCam = cam;
  badCam.cameraToWorld[0][0] = kNaN;
  EXPECT_THROW(renderer.render(scene, badCam, Region::full(8, 8), fb), Error);
  badCam = cam;
  badCam.far = badCam.near;
  EXPECT_THROW(renderer.render(scene, badCam, Region::full(8, 8), fb), Error);
  EXPECT_THROW(renderer.setSettings({.msaaSamples = 3}), Error);
  EXPECT_THROW(renderer.setSettings({.shadowMapSize = 0}), Error);
  EXPECT_THROW(FrameBuffer(0, 4), Error);
  renderer.render(scene, cam, Region::full(8, 8), fb);  // still usable
  EXPECT_EQ(fb.colour(4, 4).a, 1.0f);
}

TEST(VulkanErrors, ErrorMessagesNameTheVkResult) {
  try {
    check(VK_ERROR_OUT_OF_DEVICE_MEMORY, "vkAllocateMemory");
    FAIL() << "no throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("VK_ERROR_OUT_OF_DEVICE_MEMORY"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("vkAllocateMemory"), std::string::npos);
  }
  EXPECT_STREQ(resultName(VK_ERROR_DEVICE_LOST), "VK_ERROR_DEVICE_LOST");
}

}  // namespace
}  // namespace tsr::vk
