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

TEST(VulkanGeometryArena, ManyMeshesRemovalsAndAdditionsDrawAsAFreshScene) {
  Scene edited(device());
  Material m;
  m.baseColor = {0.7f, 0.6f, 0.3f};
  const MaterialId mat = edited.addMaterial(m);
  edited.addLight(DirectionalLight{{0.3f, -1, -0.2f}, glm::vec3(2.0f)});
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
  const MaterialId freshMat = fresh.addMaterial(m);
  fresh.addLight(DirectionalLight{{0.3f, -1, -0.2f}, glm::vec3(2.0f)});
  for (int i = 0; i < 40; ++i)
    if (i % 3 != 0) fresh.addInstance(fresh.addMesh(sphere(i)), freshMat, cell(i));
  for (int i = 0; i < 40; i += 3) fresh.addInstance(fresh.addMesh(test::uvSphere(6, 8, 0.45f)), freshMat, cell(i));

  const FrameBuffer expected = render(fresh, Visibility::All);
  EXPECT_GT(test::maxAbsDiff(expected, FrameBuffer(80, 80)), 0.1f);
  // Draw order differs between the scenes only where nothing overlaps.
  EXPECT_EQ(render(edited, Visibility::All).colourImage(), expected.colourImage());
  EXPECT_EQ(render(edited, Visibility::Guided).colourImage(), expected.colourImage());
}

}  // namespace
}  // namespace tsr::vk
