// The merged scene streamed by clusters (TraceMemory): the same image as
// the merged scene built whole, whatever the budget drops and builds again.
#include "test_scenes.hpp"

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

namespace tsr::embree::test {
namespace {

// Far more than the small budgets below hold: 48 single-use balls and
// boxes on the floor under the lamp, some of them half transparent
// (alpha-blended, decided by the tracer's filter, for camera and shadow
// rays), and a mesh used twice, so that a top level holds the merged scene
// as an instance.
struct Crowd {
  std::vector<InstanceId> balls;
  std::vector<MeshId> ballMeshes;
  std::vector<InstanceId> boxes;
};

Crowd buildCrowd(Scene& scene) {
  floorUnderLamp(scene);
  Crowd c;
  Material red, clear;
  red.baseColor = glm::vec3(0.8f, 0.2f, 0.1f);
  clear.baseColor = glm::vec3(0.2f, 0.4f, 0.9f);
  clear.alphaMode = AlphaMode::Blend;
  clear.opacity = 0.5f;
  const MaterialId redId = scene.addMaterial(red), clearId = scene.addMaterial(clear);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 8; ++j) {
      const glm::vec3 at(-3.5f + float(j), 0.3f, -2.5f + float(i));
      if ((i + j) % 2 == 0) {
        c.ballMeshes.push_back(scene.addMesh(uvSphere({0, 0, 0}, 0.3f, 200, true)));
        c.balls.push_back(
            scene.addInstance(c.ballMeshes.back(), j % 3 == 0 ? clearId : redId, glm::translate(glm::mat4(1.0f), at)));
      } else {
        c.boxes.push_back(scene.addInstance(scene.addMesh(box(at - 0.25f, at + glm::vec3(0.25f, 0.5f, 0.25f))), redId,
                                            glm::mat4(1.0f)));
      }
    }
  const MeshId shared = scene.addMesh(uvSphere({0, 0, 0}, 0.2f, 100, true));
  for (float x : {-1.0f, 1.0f}) scene.addInstance(shared, redId, glm::translate(glm::mat4(1.0f), {x, 1.5f, 0.0f}));
  return c;
}

const Camera kCamera = Camera::lookAt({0, 4, 6}, {0, 0, 0}, {0, 1, 0}, glm::radians(50.0f), 1.0f);

FrameBuffer renderCrowd(Scene& scene) {
  RenderSettings s;
  s.seed = 5;
  s.maxDepth = 4;
  Renderer renderer(s);
  FrameBuffer fb(40, 40);
  render(renderer, scene, kCamera, Region::full(fb.width(), fb.height()), fb, 2);
  return fb;
}

// About two balls a cluster, one or two clusters held; a cluster is at
// most 300 triangles and the last mesh added (25 kB estimated).
constexpr TraceMemory kSmall{.bytes = 20'000, .clusterTriangles = 300};

TEST(StreamedGeometry, RendersTheMergedScenesImage) {
  Scene whole(sharedDevice());
  buildCrowd(whole);
  const FrameBuffer expected = renderCrowd(whole);
  EXPECT_FALSE(whole.traceMemoryUse().streamed);

  Scene streamed(sharedDevice());
  buildCrowd(streamed);
  streamed.setTraceMemory(kSmall);
  const FrameBuffer got = renderCrowd(streamed);
  const TraceMemoryUse use = streamed.traceMemoryUse();
  EXPECT_TRUE(use.streamed);
  EXPECT_GE(use.clusters, 10u);
  EXPECT_GT(use.builds, use.clusters) << "the budget made clusters be built again";
  EXPECT_GT(use.evictions, 0u);
  EXPECT_LE(use.heldBytes, kSmall.bytes + 25'000) << "over the budget by the last cluster built at most";
  EXPECT_TRUE(identical(expected, got));
}

// A scene built whole and rendered turns streamed when the budget shrinks;
// edits of merged instances (moved, removed, new mesh data) partition it
// again; a larger budget builds it whole again. The image is always the
// one of a fresh scene with the same edits, built whole.
TEST(StreamedGeometry, FollowsEditsAndChangesOfTheBudget) {
  const glm::mat4 moved = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 1.2f, 1.0f));
  const auto edit = [&](Scene& scene, const Crowd& c) {
    scene.setInstanceTransform(c.balls[3], moved);
    scene.removeInstance(c.boxes[5]);
    scene.setMeshData(c.ballMeshes[7], box(glm::vec3(-0.3f), glm::vec3(0.3f, 0.9f, 0.3f)));
  };
  Scene fresh(sharedDevice());
  edit(fresh, buildCrowd(fresh));
  const FrameBuffer expected = renderCrowd(fresh);

  Scene edited(sharedDevice());
  const Crowd c = buildCrowd(edited);
  const FrameBuffer before = renderCrowd(edited);
  EXPECT_FALSE(edited.traceMemoryUse().streamed);
  edited.setTraceMemory(kSmall);
  EXPECT_TRUE(identical(before, renderCrowd(edited)));
  EXPECT_TRUE(edited.traceMemoryUse().streamed);
  edit(edited, c);
  EXPECT_TRUE(identical(expected, renderCrowd(edited)));
  EXPECT_TRUE(edited.traceMemoryUse().streamed);
  EXPECT_FALSE(identical(before, expected)) << "the edits must be visible";

  edited.setTraceMemory(TraceMemory{});
  EXPECT_TRUE(identical(expected, renderCrowd(edited)));
  EXPECT_FALSE(edited.traceMemoryUse().streamed);
}

TEST(StreamedGeometry, RefusesAnEmptyBudget) {
  Scene scene(sharedDevice());
  EXPECT_THROW(scene.setTraceMemory({.bytes = 0, .clusterTriangles = 100}), Error);
  EXPECT_THROW(scene.setTraceMemory({.bytes = 100, .clusterTriangles = 0}), Error);
}

}  // namespace
}  // namespace tsr::embree::test
