// Meshes share the geometry arena's blocks: more meshes than the first
// block holds, removals and additions in between, and the image is the one
// of a scene built afresh with what is left.
#include "test_util.hpp"

#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace tsr::vk {
namespace {

using test::device;

const Camera kCam = Camera::lookAt({0, 6, 9}, {0, 0, 0}, {0, 1, 0}, 0.9f, 1.0f);

glm::mat4 cell(int i) { return glm::translate(glm::mat4(1.0f), {float(i % 8) - 3.5f, 0, float(i / 8) - 2.5f}); }

// Sphere i: 41 x 50 vertices (2,091), so 40 of them overflow a 65,536-vertex block.
MeshData sphere(int i) { return test::uvSphere(40, 49 + i % 3, 0.3f + 0.01f * float(i % 5)); }

FrameBuffer render(Scene& scene, Visibility visibility) {
  Renderer r(device(), RenderSettings{.visibility = visibility});
  FrameBuffer fb(80, 80);
  for (int i = 0; i < 2; ++i) r.render(scene, kCam, Region::full(80, 80), fb);
  return fb;
}

// The tests' one material and light, added to a scene; returns the material.
MaterialId ochreUnderTheSun(Scene& scene) {
  Material m;
  m.baseColor = {0.7f, 0.6f, 0.3f};
  scene.addLight(DirectionalLight{{0.3f, -1, -0.2f}, glm::vec3(2.0f)});
  return scene.addMaterial(m);
}

TEST(VulkanGeometryArena, ManyMeshesRemovalsAndAdditionsDrawAsAFreshScene) {
  Scene edited(device());
  const MaterialId mat = ochreUnderTheSun(edited);
  std::vector<MeshId> meshes;
  std::vector<InstanceId> instances;
  for (int i = 0; i < 40; ++i) {
    meshes.push_back(edited.addMesh(sphere(i)));
    instances.push_back(edited.addInstance(meshes.back(), mat, cell(i)));
  }
  render(edited, Visibility::All);
  // Drop every third sphere, then add new ones in their cells (with another shape).
  for (int i = 0; i < 40; i += 3) {
    edited.removeInstance(instances[i]);
    edited.removeMesh(meshes[i]);
    edited.addInstance(edited.addMesh(test::uvSphere(6, 8, 0.45f)), mat, cell(i));
  }

  Scene fresh(device());
  const MaterialId freshMat = ochreUnderTheSun(fresh);
  for (int i = 0; i < 40; ++i)
    if (i % 3 != 0) fresh.addInstance(fresh.addMesh(sphere(i)), freshMat, cell(i));
  for (int i = 0; i < 40; i += 3) fresh.addInstance(fresh.addMesh(test::uvSphere(6, 8, 0.45f)), freshMat, cell(i));

  const FrameBuffer expected = render(fresh, Visibility::All);
  EXPECT_GT(test::maxAbsDiff(expected, FrameBuffer(80, 80)), 0.1f);
  // Draw order differs between the scenes only where nothing overlaps.
  EXPECT_EQ(render(edited, Visibility::All).colourImage(), expected.colourImage());
  EXPECT_EQ(render(edited, Visibility::Guided).colourImage(), expected.colourImage());
}

TEST(VulkanGeometryArena, SmallMeshesHold16BitIndicesLargeOnes32BitAndDrawTogether) {
  Scene scene(device());
  const MaterialId mat = ochreUnderTheSun(scene);
  // A first block holds 65,536 vertices (14 or 16 bytes each: a position
  // and a uv as 16-bit fractions of their boxes, an octahedral normal) and
  // three indices a vertex, of 2 bytes for meshes that fit.
  const std::uint64_t vertex = device()->positionBytes() + 4u + 4u;
  scene.addInstance(scene.addMesh(sphere(0)), mat, cell(0));
  EXPECT_EQ(scene.geometryBytesHeld(), 65536u * vertex + 3u * 65536u * 2u);
  // 301 x 251 = 75,551 vertices: a block of its size, of 32-bit indices.
  const MeshData big = test::uvSphere(300, 250, 1.2f);
  ASSERT_GT(big.positions.size(), 65536u);
  scene.addInstance(scene.addMesh(big), mat, cell(20));
  EXPECT_EQ(scene.geometryBytesHeld(),
            65536u * vertex + 3u * 65536u * 2u + big.positions.size() * vertex + big.indices.size() * 4u);
  scene.addInstance(scene.addMesh(sphere(1)), mat, cell(7));

  const FrameBuffer all = render(scene, Visibility::All);
  EXPECT_EQ(render(scene, Visibility::Guided).colourImage(), all.colourImage());
  // The large sphere is drawn whole: the pixel at its centre is lit, as
  // in a scene of it alone.
  Scene alone(device());
  const MaterialId aloneMat = ochreUnderTheSun(alone);
  alone.addInstance(alone.addMesh(big), aloneMat, cell(20));
  const FrameBuffer only = render(alone, Visibility::All);
  EXPECT_GT(test::maxAbsDiff(only, FrameBuffer(80, 80)), 0.1f);
  const auto background = FrameBuffer(80, 80).colourImage(), alonePixels = only.colourImage(),
             together = all.colourImage();
  int sameLit = 0, lit = 0;
  for (std::size_t i = 0; i < alonePixels.size(); ++i) {
    if (alonePixels[i] == background[i]) continue;
    ++lit;
    sameLit += alonePixels[i] == together[i];
  }
  EXPECT_GT(lit, 200);
  EXPECT_GT(sameLit, lit * 9 / 10) << "the large sphere's pixels differ from it drawn alone";
}

}  // namespace
}  // namespace tsr::vk
