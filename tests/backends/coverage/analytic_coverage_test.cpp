// Pixel counts known in closed form: quads whose edges project half-way
// between pixel centres of a 100x100 image seen through the window [-1,1]^2.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "test_scenes.hpp"
#include "tsr/cov/ranking.hpp"

using namespace tsr::cov;
using tsr::cov::test::quad;

namespace {
const Region kFull = Region::full(100, 100);

std::uint64_t pixelsOf(const std::vector<Coverage>& ranking, ObjectId id) {
  for (const auto& c : ranking)
    if (c.id == id) return c.pixels;
  return 0;
}
}  // namespace

TEST(AnalyticCoverage, QuadCoversExactlyItsPixels) {
  EmbreeIdRenderer r;
  // At z = -2 the quad [-1,1]^2 projects to [-0.5,0.5]^2: 50x50 pixels.
  r.addInstance({r.addMesh(quad(-1, 1, -1, 1, -2)), glm::mat4(1.0f), 7, false});
  IdBuffer ids = r.render(test::straightCamera(), kFull);
  auto ranking = rank(ids);
  ASSERT_EQ(ranking.size(), 1u);
  EXPECT_EQ(ranking[0].id, 7u);
  EXPECT_EQ(ranking[0].pixels, 2500u);
  EXPECT_DOUBLE_EQ(ranking[0].fraction, 0.25);
  EXPECT_EQ(ids.id(25, 25), 7u);
  EXPECT_EQ(ids.id(24, 25), kBackground);
  EXPECT_EQ(ids.id(74, 74), 7u);
  EXPECT_EQ(ids.id(75, 74), kBackground);
  EXPECT_NEAR(ids.depth[ids.index(50, 50)], 2.0f, 1e-5f);
  EXPECT_EQ(ids.depth[ids.index(0, 0)], kNoDepth);
}

TEST(AnalyticCoverage, OffAxisWindowAndTransformedCamera) {
  EmbreeIdRenderer r;
  r.addInstance({r.addMesh(quad(-1, 1, -1, 1, 0)), glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, 0)), 3, false});
  // Camera 2 units in front of the quad; the window covers only x in [0, 1]
  // at near 1, i.e. x in [0, 2] at the quad: the right half of the image
  // column range sees x in [0, 1] -> 50 of 100 columns, rows [-0.5, 0.5] -> 50.
  Camera c;
  c.cameraToWorld = glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, 2));
  c.left = 0.0f;
  c.right = 1.0f;
  auto ranking = rank(r.render(c, kFull));
  ASSERT_EQ(ranking.size(), 1u);
  EXPECT_EQ(ranking[0].pixels, 50u * 50u);
}

TEST(AnalyticCoverage, NearerQuadWins) {
  EmbreeIdRenderer r;
  MeshId a = r.addMesh(quad(-1, 1, -1, 1, -2));  // projects to [-0.5,0.5]^2
  MeshId b = r.addMesh(quad(0, 3, -3, 3, -3));   // projects to [0,1]x[-1,1]
  r.addInstance({a, glm::mat4(1.0f), 1, false});
  InstanceId ib = r.addInstance({b, glm::mat4(1.0f), 2, false});
  auto ranking = rank(r.render(test::straightCamera(), kFull));
  ASSERT_EQ(ranking.size(), 2u);
  EXPECT_EQ(pixelsOf(ranking, 1), 2500u);
  EXPECT_EQ(pixelsOf(ranking, 2), 5000u - 1250u);
  EXPECT_EQ(ranking[0].id, 2u) << "sorted by pixels";

  // Bring b in front (z = -1.5 keeps its projection): a loses the overlap.
  r.setInstanceTransform(ib, glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 1.5f)) *
                                 glm::scale(glm::mat4(1.0f), glm::vec3(0.5f, 0.5f, 1.0f)));
  // b scaled by 0.5 in x,y and moved to z = -1.5: x in [0,1.5]/1.5, y in [-1.5,1.5]/1.5.
  ranking = rank(r.render(test::straightCamera(), kFull));
  EXPECT_EQ(pixelsOf(ranking, 2), 5000u);
  EXPECT_EQ(pixelsOf(ranking, 1), 1250u);
}

TEST(AnalyticCoverage, TransparentInFrontDoesNotOcclude) {
  EmbreeIdRenderer r;
  InstanceId front = r.addInstance({r.addMesh(quad(-2, 2, -2, 2, -2)), glm::mat4(1.0f), 1, true});  // covers all
  r.addInstance({r.addMesh(quad(-1.5f, 1.5f, -1.5f, 1.5f, -3)), glm::mat4(1.0f), 2, false});
  auto ranking = rank(r.render(test::straightCamera(), kFull));
  ASSERT_EQ(ranking.size(), 1u);
  EXPECT_EQ(ranking[0].id, 2u);
  EXPECT_EQ(ranking[0].pixels, 2500u);

  r.setInstanceTransparent(front, false);
  ranking = rank(r.render(test::straightCamera(), kFull));
  ASSERT_EQ(ranking.size(), 1u);
  EXPECT_EQ(ranking[0].id, 1u);
  EXPECT_EQ(ranking[0].pixels, 10000u);
}

TEST(AnalyticCoverage, InstancesSharingAnObjectAddUp) {
  EmbreeIdRenderer r;
  MeshId m = r.addMesh(quad(-0.5f, 0.5f, -0.5f, 0.5f, -1));  // 50x50 pixels where placed
  for (float x : {-0.5f, 0.5f}) r.addInstance({m, glm::translate(glm::mat4(1.0f), glm::vec3(x, 0, 0)), 9, false});
  r.addInstance({m, glm::translate(glm::mat4(1.0f), glm::vec3(0, 1.0f, 0)), 4, false});
  auto ranking = rank(r.render(test::straightCamera(), kFull));
  ASSERT_EQ(ranking.size(), 2u);
  EXPECT_EQ(ranking[0].id, 9u);
  EXPECT_EQ(ranking[0].pixels, 2u * 2500u);
  EXPECT_EQ(ranking[1].id, 4u);
  EXPECT_EQ(ranking[1].pixels, 50u * 25u) << "the upper quad is half off-screen";
}

TEST(AnalyticCoverage, ObjectRenumberingNeedsNoRebuild) {
  EmbreeIdRenderer r;
  InstanceId i = r.addInstance({r.addMesh(quad(-1, 1, -1, 1, -2)), glm::mat4(1.0f), 7, false});
  r.render(test::straightCamera(), kFull);
  r.setInstanceObject(i, 8);
  auto ranking = rank(r.render(test::straightCamera(), kFull));
  ASSERT_EQ(ranking.size(), 1u);
  EXPECT_EQ(ranking[0].id, 8u);
}
