// The workload figures and image from a given list of tiles: sums per node,
// the balance, colours told apart, and the drawing's properties.
#include <gtest/gtest.h>

#include "tsr/cluster/wall_layout.hpp"
#include "tsr/cluster/workload.hpp"
#include "wall/workload_check.hpp"

namespace tsr::cluster::test {
namespace {

TEST(Workload, SumsPerNodeAndTheBalanceOverTheNodesTakingPart) {
  const std::vector<TileWork> tiles{{{0, 0, 16, 16}, 0, 0.3, 4, 1000},
                                    {{16, 0, 32, 16}, 0, 0.1, 4, 500},
                                    {{0, 16, 16, 24}, 1, 0.2, 8, 700},
                                    {{16, 16, 32, 24}, TileWork::kNoNode, 0, 0, 0}};
  const FrameWorkload w = summarizeWorkload(tiles, {1.0, 0.5}, {0, 1, 2}, 3);
  ASSERT_EQ(w.nodes.size(), 3u);
  EXPECT_EQ(w.nodes[0].tiles, 2u);
  EXPECT_EQ(w.nodes[0].pixels, 512u);
  EXPECT_EQ(w.nodes[0].samples, 512u * 4);
  EXPECT_EQ(w.nodes[0].rays, 1500u);
  EXPECT_DOUBLE_EQ(w.nodes[0].seconds, 0.4);
  EXPECT_DOUBLE_EQ(w.nodes[0].busySeconds, 1.0);
  EXPECT_EQ(w.nodes[1].pixels, 128u);
  EXPECT_EQ(w.nodes[1].samples, 128u * 8);
  EXPECT_EQ(w.nodes[2].tiles, 0u);  // online, yet without work: it counts, with 0 s
  EXPECT_DOUBLE_EQ(w.balance, 0.4 / ((0.4 + 0.2 + 0.0) / 3));
  // Over the first two only.
  EXPECT_DOUBLE_EQ(summarizeWorkload(tiles, {}, {0, 1}, 3).balance, 0.4 / 0.3);
  // Nothing measured: even.
  EXPECT_DOUBLE_EQ(summarizeWorkload({}, {}, {0, 1}, 2).balance, 1.0);
}

TEST(Workload, NodeColoursAreToldApartByHue) {
  // Brightness says a tile's time, so nodes differ in chromaticity: the
  // first eight are each nearest to themselves, by a margin.
  for (std::size_t a = 0; a < 8; ++a) {
    EXPECT_EQ(nodeShown(glm::vec4(nodeColour(a) * 0.2f, 1.0f), 8), a) << "node " << a;
    for (std::size_t b = a + 1; b < 8; ++b) {
      const glm::vec3 d = chromaticity(nodeColour(a)) - chromaticity(nodeColour(b));
      EXPECT_GT(glm::length(d), 0.04f) << "nodes " << a << " and " << b;
    }
  }
}

TEST(Workload, TheImageColoursEachTileByItsNodeAndShadesItByItsTime) {
  const auto rects = tileGrid(50, 30, 16);
  std::vector<TileWork> tiles;
  for (std::size_t i = 0; i < rects.size(); ++i) tiles.push_back({rects[i], i % 3, 0.01 * double(i + 1), 2, 100});
  const auto image = drawWorkload(tiles, 50, 30);
  expectCoveredExactlyOnce(tiles, 50, 30, "grid");
  expectWorkloadImageMatches(image, 50, 30, tiles, 3, "grid");
  // Quicker tiles are darker, down to a fifth.
  const glm::vec4 quick = image[0], slow = image[std::size_t{rects.back().y0} * 50 + rects.back().x0];
  EXPECT_LT(quick.r + quick.g + quick.b, slow.r + slow.g + slow.b);
  EXPECT_FLOAT_EQ(workloadShade(0, 2), 0.2f);
  EXPECT_FLOAT_EQ(workloadShade(2, 2), 1.0f);
  EXPECT_FLOAT_EQ(workloadShade(1, 0), 1.0f);  // nothing measured: full colour
}

TEST(Workload, PixelsOfNoTileOrOfAGivenUpOneStayBlack) {
  const std::vector<TileWork> tiles{{{0, 0, 8, 8}, 1, 0.5, 1, 1}, {{10, 0, 20, 8}, TileWork::kNoNode, 0, 0, 0}};
  const auto image = drawWorkload(tiles, 20, 10);
  EXPECT_EQ(image[std::size_t{9} * 20 + 9], glm::vec4(0, 0, 0, 1));  // the gap
  EXPECT_EQ(image[15], glm::vec4(0, 0, 0, 1));                       // given up
  EXPECT_EQ(glm::vec3(image[0]), nodeColour(1));
}

}  // namespace
}  // namespace tsr::cluster::test
