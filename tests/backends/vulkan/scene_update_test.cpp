#include "test_util.hpp"

#include "tsr/vk/error.hpp"
#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"

#include <gtest/gtest.h>

namespace tsr::vk {
namespace {

using test::device;

const Camera kCam = Camera::lookAt({0, 1.5f, 5}, {0, 0, 0}, {0, 1, 0}, 0.8f, 1.0f);

struct Built {
  MeshId sphere, ground;
  InstanceId moving;
};

Built build(Scene& scene, const glm::mat4& movingTransform) {
  Built b;
  b.sphere = scene.addMesh(test::uvSphere(12, 16, 0.6f));
  b.ground = scene.addMesh(test::groundQuad(0, 0, 3, -0.6f));
  Material m;
  m.baseColor = {0.3f, 0.7f, 0.4f};
  MaterialId mat = scene.addMaterial(m);
  scene.addInstance(b.sphere, mat, glm::translate(glm::mat4(1.0f), {-1.2f, 0, 0}));
  b.moving = scene.addInstance(b.sphere, mat, movingTransform);
  scene.addInstance(b.ground, scene.addMaterial({}), glm::mat4(1.0f));
  scene.addLight(DirectionalLight{{0.2f, -1, -0.4f}, glm::vec3(2.0f)});
  return b;
}

FrameBuffer render(Scene& scene) {
  Renderer renderer(device());
  FrameBuffer fb(64, 64);
  renderer.render(scene, kCam, Region::full(64, 64), fb);
  return fb;
}

TEST(VulkanSceneUpdate, InstanceMoveWritesOnlyTheInstanceRecord) {
  const glm::mat4 before = glm::translate(glm::mat4(1.0f), {1.0f, 0, 0});
  const glm::mat4 after =
      glm::translate(glm::mat4(1.0f), {0.3f, 0.4f, 0.8f}) * glm::scale(glm::mat4(1.0f), glm::vec3(0.7f));
  Scene scene(device());
  Built b = build(scene, before);
  FrameBuffer first = render(scene);

  const std::uint64_t geometry = scene.geometryBytesUploaded();
  const std::uint64_t instances = scene.instanceBytesWritten();
  scene.setInstanceTransform(b.moving, after);
  EXPECT_EQ(scene.geometryBytesUploaded(), geometry);
  EXPECT_EQ(scene.instanceBytesWritten(), instances + 176);  // model and normal matrices, the mesh's boxes
  FrameBuffer moved = render(scene);
  EXPECT_GT(test::maxAbsDiff(first, moved), 0.1f);

  Scene fresh(device());
  build(fresh, after);
  FrameBuffer expected = render(fresh);
  EXPECT_EQ(moved.colourImage(), expected.colourImage());
  EXPECT_EQ(moved.depthImage(), expected.depthImage());
}

TEST(VulkanSceneUpdate, VertexRangeUpdateUploadsOnlyThatRange) {
  MeshData ground = test::groundQuad(0, 0, 3, -0.6f);
  Scene scene(device());
  Built b = build(scene, glm::mat4(1.0f));
  FrameBuffer first = render(scene);

  // Lift the two far corners of the ground: a slope.
  const glm::vec3 n = glm::normalize(glm::vec3(0, 6, 1.1f));
  MeshData slope = ground;
  slope.positions[2] = {3, 0.5f, -3};
  slope.positions[3] = {-3, 0.5f, -3};
  slope.normals[2] = slope.normals[3] = n;
  const std::uint64_t geometry = scene.geometryBytesUploaded();
  scene.updateMeshVertices(b.ground, {.positions = slope.positions, .normals = slope.normals, .first = 2, .count = 2});
  // The flat ground's box has no height: lifting corners grows it, so its
  // four positions are stored again (6 or 8 bytes each), and two normals (4 bytes).
  EXPECT_EQ(scene.geometryBytesUploaded(), geometry + 4 * device()->positionBytes() + 2 * 4);
  FrameBuffer edited = render(scene);
  EXPECT_GT(test::maxAbsDiff(first, edited), 0.05f);

  // The same edit made before upload, in a scene built from scratch.
  Scene rebuilt(device());
  MeshId sphere = rebuilt.addMesh(test::uvSphere(12, 16, 0.6f));
  MeshId g = rebuilt.addMesh(slope);
  Material m;
  m.baseColor = {0.3f, 0.7f, 0.4f};
  MaterialId mat = rebuilt.addMaterial(m);
  rebuilt.addInstance(sphere, mat, glm::translate(glm::mat4(1.0f), {-1.2f, 0, 0}));
  rebuilt.addInstance(sphere, mat, glm::mat4(1.0f));
  rebuilt.addInstance(g, rebuilt.addMaterial({}), glm::mat4(1.0f));
  rebuilt.addLight(DirectionalLight{{0.2f, -1, -0.4f}, glm::vec3(2.0f)});
  FrameBuffer expected = render(rebuilt);
  EXPECT_EQ(edited.colourImage(), expected.colourImage());
}

TEST(VulkanSceneUpdate, RemovedInstanceDisappearsAndMaterialSwapRecolours) {
  Scene scene(device());
  Built b = build(scene, glm::translate(glm::mat4(1.0f), {1.0f, 0, 0}));
  const glm::vec2 px = test::project(kCam, Region::full(64, 64), {1.0f, 0, 0.59f});
  FrameBuffer before = render(scene);
  Material blue;
  blue.baseColor = {0.0f, 0.0f, 1.0f};
  scene.setInstanceMaterial(b.moving, scene.addMaterial(blue));
  FrameBuffer recoloured = render(scene);
  EXPECT_GT(before.colour(int(px.x), int(px.y)).g, 0.05f);
  EXPECT_EQ(recoloured.colour(int(px.x), int(px.y)).g, 0.0f);
  EXPECT_GT(recoloured.colour(int(px.x), int(px.y)).b, 0.05f);
  scene.removeInstance(b.moving);
  EXPECT_THROW(scene.setInstanceTransform(b.moving, glm::mat4(1.0f)), Error);
  FrameBuffer removed = render(scene);
  EXPECT_GT(removed.depth(int(px.x), int(px.y)), before.depth(int(px.x), int(px.y)) + 0.3f);
  EXPECT_EQ(scene.instanceCount(), 2u);
}

}  // namespace
}  // namespace tsr::vk

namespace tsr::vk {
namespace {

// An instance moved within the scene's bounds, removed or added redraws the
// shadow maps only where it was and is: fewer triangles, and the image a
// renderer that draws the maps whole makes of the same scene.
TEST(VulkanSceneUpdate, InstanceEditsRedrawOnlyTheirShadowFootprints) {
  Scene scene(device());
  Built b = build(scene, glm::translate(glm::mat4(1.0f), {1.0f, 0, 0}));
  Renderer renderer(device());
  FrameBuffer fb(64, 64);
  renderer.render(scene, kCam, Region::full(64, 64), fb);
  const std::uint64_t whole = renderer.lastStats().shadowTriangles;
  ASSERT_GT(whole, 0u);
  auto expectAsDrawnWhole = [&](const char* what) {
    renderer.render(scene, kCam, Region::full(64, 64), fb);
    const std::uint64_t drawn = renderer.lastStats().shadowTriangles;
    EXPECT_GT(drawn, 0u) << what;
    EXPECT_LT(drawn, whole) << what;
    const FrameBuffer expected = render(scene);  // a new renderer: the maps drawn whole
    EXPECT_EQ(fb.colourImage(), expected.colourImage()) << what;
    EXPECT_EQ(fb.depthImage(), expected.depthImage()) << what;
  };
  // Away from the other sphere, inside the ground: the scene's bounds stay.
  scene.setInstanceTransform(b.moving, glm::translate(glm::mat4(1.0f), {2.0f, 0, 1.5f}));
  expectAsDrawnWhole("moved");
  const InstanceId added =
      scene.addInstance(b.sphere, scene.addMaterial({}), glm::translate(glm::mat4(1.0f), {1.5f, 0, -1.8f}));
  expectAsDrawnWhole("added");
  scene.removeInstance(b.moving);
  expectAsDrawnWhole("removed");
  scene.setInstanceObject(added, 7);  // no caster changed: nothing drawn again
  renderer.render(scene, kCam, Region::full(64, 64), fb);
  EXPECT_EQ(renderer.lastStats().shadowTriangles, 0u);
}

}  // namespace
}  // namespace tsr::vk
