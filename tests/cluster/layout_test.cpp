// Wall layout, tile grid, the balancer and the config parser.
#include <gtest/gtest.h>

#include "tsr/cluster/cluster_config.hpp"
#include "tsr/cluster/tile_balancer.hpp"
#include "tsr/cluster/wall_layout.hpp"

namespace tsr::cluster {
namespace {

TEST(WallLayout, TilesCoverTheFrameExceptTheBezels) {
  auto rects = wallLayout(64, 64, 2, 2, 0);
  ASSERT_EQ(rects.size(), 4u);
  EXPECT_EQ(rects[0], (med::PixelRect{0, 0, 32, 32}));
  EXPECT_EQ(rects[3], (med::PixelRect{32, 32, 64, 64}));
  auto gapped = wallLayout(70, 40, 2, 1, 6);
  EXPECT_EQ(gapped[0], (med::PixelRect{0, 0, 32, 40}));
  EXPECT_EQ(gapped[1], (med::PixelRect{38, 0, 70, 40}));
  EXPECT_THROW(wallLayout(10, 10, 2, 2, 10), std::invalid_argument);
}

TEST(TileGrid, CoversEveryPixelOnce) {
  auto tiles = tileGrid(70, 33, 16);
  std::size_t area = 0;
  for (const auto& t : tiles) area += std::size_t{t.width()} * t.height();
  EXPECT_EQ(area, 70u * 33u);
  EXPECT_EQ(tiles.size(), 5u * 3u);
}

TEST(TileBalancer, MovesWorkFromTheBusiestNodeAndStaysPut) {
  TileBalancer b(16, 0.05, 16);
  b.setNodes({0, 1});
  for (std::size_t t = 0; t < 16; ++t) b.record(t, t < 4 ? 8.0 : 1.0);  // cost in node 0's first tiles
  for (int frame = 0; frame < 5; ++frame) {
    for (std::size_t t = 0; t < 16; ++t) b.record(t, t < 4 ? 8.0 : 1.0);
    b.rebalance();
  }
  EXPECT_LE(b.imbalance(), 1.15);
  // Balanced: further frames with the same costs move nothing.
  EXPECT_EQ(b.rebalance(), 0u);
}

TEST(TileBalancer, LostNodesTilesGoToTheOthers) {
  TileBalancer b(9, 0.05, 2);
  b.setNodes({0, 1, 2});
  auto moved = b.removeNode(1);
  EXPECT_EQ(moved.size(), 3u);
  for (std::size_t t = 0; t < 9; ++t) EXPECT_NE(b.owner(t), 1u);
  b.setNodes({0, 2, 5});  // a new node starts empty and gets work by rebalancing
  EXPECT_TRUE(b.tilesOf(5).empty());
  b.rebalance();
  EXPECT_FALSE(b.tilesOf(5).empty());
}

TEST(ClusterConfig, ParsesModesNodesAndParameters) {
  ClusterConfig c = parseClusterConfig(R"({
    "mode": "tiled", "backend": "embree", "parameters": {"spp": 2, "seed": 3},
    "nodes": [{"address": "127.0.0.1:1"}, {"address": "127.0.0.1:2", "parameters": {"spp": 8}}],
    "wall": {"columns": 2, "rows": 1, "bezel": 4},
    "timeouts": {"frameMs": 500}})");
  EXPECT_EQ(c.mode, ClusterMode::Tiled);
  ASSERT_EQ(c.nodes.size(), 2u);
  EXPECT_EQ(c.nodes[0].parameters.getInt("spp", 0), 2);
  EXPECT_EQ(c.nodes[1].parameters.getInt("spp", 0), 8);
  EXPECT_EQ(c.nodes[1].parameters.getInt("seed", 0), 3);
  EXPECT_EQ(c.wall.bezel, 4u);
  EXPECT_EQ(c.timeouts.frame.count(), 500);
  c.replaceAddresses({parseNodeAddress("10.0.0.1:5"), parseNodeAddress("10.0.0.2:6")});
  EXPECT_EQ(c.nodes[1].address.text(), "10.0.0.2:6");
}

TEST(ClusterConfig, RejectsWhatCannotWork) {
  EXPECT_THROW(parseClusterConfig("{"), ConfigError);
  EXPECT_THROW(parseClusterConfig(R"({"mode": "spiral", "nodes": [{}]})"), ConfigError);
  EXPECT_THROW(parseClusterConfig(R"({"nodes": []})"), ConfigError);
  EXPECT_THROW(parseClusterConfig(R"({"mode": "tiled", "nodes": [{}], "wall": {"columns": 2, "rows": 2}})"), ConfigError);
  EXPECT_THROW(parseClusterConfig(R"({"nodes": [{"address": "nohost"}]})"), ConfigError);
  EXPECT_THROW(parseClusterConfig(R"({"nodes": [{"parameters": {"x": [1]}}]})"), ConfigError);
}

}  // namespace
}  // namespace tsr::cluster

namespace tsr::cluster {
namespace {

TEST(ClusterConfig, ShippedConfigsParse) {
  for (const char* name : {"cooperative-2.json", "wall-2x2.json", "stereo-pair.json", "mixed-backends.json"}) {
    ClusterConfig c = loadClusterConfig(std::string(TSR_CONFIG_DIR) + "/" + name);
    EXPECT_FALSE(c.nodes.empty()) << name;
  }
  EXPECT_EQ(loadClusterConfig(std::string(TSR_CONFIG_DIR) + "/wall-2x2.json").mode, ClusterMode::Tiled);
  EXPECT_THROW(loadClusterConfig("/nonexistent.json"), ConfigError);
}

}  // namespace
}  // namespace tsr::cluster
