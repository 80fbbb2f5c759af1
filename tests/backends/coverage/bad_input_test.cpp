// Invalid arguments are Errors with a message, and leave the scene usable.
#include <gtest/gtest.h>

#include <cmath>

#include "test_scenes.hpp"
#include "tsr/cov/error.hpp"

using namespace tsr::cov;

TEST(BadInput, IsRejectedWithoutHarm) {
  EmbreeIdRenderer r;
  MeshId m = r.addMesh(test::quad(-1, 1, -1, 1, -2));
  MeshData outOfRange = test::quad(0, 1, 0, 1, 0);
  outOfRange.indices[2] = 4;
  EXPECT_THROW(r.addMesh(outOfRange), Error);
  EXPECT_THROW(r.addMesh(MeshData{}), Error);
  MeshData nan = test::quad(0, 1, 0, 1, 0);
  nan.positions[1].x = NAN;
  EXPECT_THROW(r.addMesh(nan), Error);
  EXPECT_THROW(r.addInstance({m, glm::mat4(1.0f), kBackground, false}), Error);
  EXPECT_THROW(r.addInstance({MeshId(42), glm::mat4(1.0f), 1, false}), Error);
  glm::mat4 inf(1.0f);
  inf[3][0] = INFINITY;
  EXPECT_THROW(r.addInstance({m, inf, 1, false}), Error);
  InstanceId i = r.addInstance({m, glm::mat4(1.0f), 1, false});
  EXPECT_THROW(r.removeMesh(m), Error) << "still used";
  EXPECT_THROW(r.setInstanceObject(i, kBackground), Error);
  EXPECT_THROW(r.updateMeshVertices(m, {.positions = std::vector<glm::vec3>(4), .first = 3, .count = 2}), Error);
  EXPECT_THROW(r.setSettings({0, 6}), Error);
  EXPECT_THROW(r.setSettings({-1, 32}), Error);

  EXPECT_THROW(r.render(test::straightCamera(), Region{10, 10, 0, 0, 11, 10}), Error);
  EXPECT_THROW(r.render(test::straightCamera(), Region{10, 10, 5, 5, 5, 6}), Error);
  EXPECT_THROW(r.render(test::straightCamera(), Region{}), Error);
  Camera flat = test::straightCamera();
  flat.right = flat.left;
  EXPECT_THROW(r.render(flat, Region::full(10, 10)), Error);
  Camera behind = test::straightCamera();
  behind.near = 0.0f;
  EXPECT_THROW(r.render(behind, Region::full(10, 10)), Error);

  // Still renders what was valid.
  IdBuffer ids = r.render(test::straightCamera(), Region::full(100, 100));
  EXPECT_EQ(std::count(ids.ids.begin(), ids.ids.end(), 1u), 2500);
  r.removeInstance(i);
  EXPECT_THROW(r.removeInstance(i), Error);
  r.removeMesh(m);
  EXPECT_EQ(r.meshCount(), 0u);
  ids = r.render(test::straightCamera(), Region::full(100, 100));
  EXPECT_EQ(std::count(ids.ids.begin(), ids.ids.end(), kBackground), 10000);
}
