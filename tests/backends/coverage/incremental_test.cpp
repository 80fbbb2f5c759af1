// Edits to a rendered scene give the same ids as building the edited scene
// from scratch.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "test_scenes.hpp"

using namespace tsr::cov;

namespace {
const Region kRegion = Region::full(160, 120);

IdBuffer fresh(const test::RandomScene& scene) {
  EmbreeIdRenderer r;
  test::load(r, scene);
  return r.render(test::straightCamera(), kRegion);
}

class Incremental : public ::testing::Test {
 protected:
  test::RandomScene scene = test::randomScene(21, 150, 150);
  EmbreeIdRenderer renderer;
  std::vector<InstanceId> handles;
  IdBuffer before;
  void SetUp() override {
    handles = test::load(renderer, scene);
    before = renderer.render(test::straightCamera(), kRegion);
  }
  void check(const char* what) {
    IdBuffer after = renderer.render(test::straightCamera(), kRegion);
    EXPECT_EQ(after.ids, fresh(scene).ids) << what;
    EXPECT_NE(after.ids, before.ids) << what << ": the edit is visible";
  }
};
}  // namespace

TEST_F(Incremental, TransformEdits) {
  for (std::size_t i = 0; i < scene.instances.size(); i += 7) {
    scene.instances[i].transform = glm::translate(scene.instances[i].transform, glm::vec3(0.3f, -0.2f, 0.1f));
    renderer.setInstanceTransform(handles[i], scene.instances[i].transform);
  }
  check("transforms");
}

TEST_F(Incremental, TransparencyToggles) {
  for (std::size_t i = 0; i < scene.instances.size(); i += 3) {
    scene.instances[i].transparent = true;
    renderer.setInstanceTransparent(handles[i], true);
  }
  check("transparent");
  for (std::size_t i = 0; i < scene.instances.size(); i += 6) {
    scene.instances[i].transparent = false;
    renderer.setInstanceTransparent(handles[i], false);
  }
  check("opaque again");
}

TEST_F(Incremental, RemoveAndAddInstances) {
  // Removing from the end keeps the fresh scene's instance order the same.
  for (int k = 0; k < 40; ++k) {
    renderer.removeInstance(handles.back());
    handles.pop_back();
    scene.instances.pop_back();
  }
  Instance big{MeshId(0), glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -3)), glm::vec3(2.0f)), 999,
               false};
  scene.instances.push_back(big);
  big.mesh = MeshId(0);  // the first mesh loaded keeps handle 0
  renderer.addInstance(big);
  check("remove and add");
  EXPECT_EQ(renderer.instanceCount(), scene.instances.size());
}

TEST_F(Incremental, MeshEdits) {
  // Vertex range update of the soup (mesh 2), whole replacement of the quad.
  auto& soup = scene.meshes[2];
  for (std::size_t v = 0; v < 30; ++v) soup.positions[v] *= 1.8f;
  renderer.updateMeshVertices(MeshId(2), {.positions = soup.positions, .count = 30});
  scene.meshes[0] = test::quad(-0.9f, 0.9f, -0.2f, 0.2f, 0.0f);
  renderer.setMeshData(MeshId(0), scene.meshes[0]);
  check("meshes");
}
