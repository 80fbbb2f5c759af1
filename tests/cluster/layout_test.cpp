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
  EXPECT_EQ(c.nodes[0].parameters.all().at("spp"), tsr::med::ParameterValue(std::int64_t{2}));
  EXPECT_EQ(c.nodes[1].parameters.all().at("spp"), tsr::med::ParameterValue(std::int64_t{8}));
  EXPECT_EQ(c.nodes[1].parameters.all().at("seed"), tsr::med::ParameterValue(std::int64_t{3}));
  EXPECT_EQ(c.wall.bezel, 4u);
  EXPECT_EQ(c.timeouts.frame.count(), 500);
  c.replaceAddresses({parseNodeAddress("10.0.0.1:5"), parseNodeAddress("10.0.0.2:6")});
  EXPECT_EQ(c.nodes[1].address.text(), "10.0.0.2:6");
}

TEST(ClusterConfig, TheConfigsParametersAreItsBackEndsOnly) {
  // A rasterising node in a path tracer's config gets none of its spp,
  // seed or depth, which its back-end would refuse.
  ClusterConfig c = parseClusterConfig(R"({
    "mode": "stereo", "backend": "embree", "parameters": {"spp": 2, "seed": 3},
    "nodes": [{"address": "127.0.0.1:1"}, {"address": "127.0.0.1:2", "backend": "vulkan", "parameters": {"msaa": 4}}]})");
  EXPECT_EQ(c.nodes[0].parameters.all().count("spp"), 1u);
  EXPECT_EQ(c.nodes[1].parameters.all().count("spp"), 0u);
  EXPECT_EQ(c.nodes[1].parameters.all().count("seed"), 0u);
  EXPECT_EQ(c.nodes[1].parameters.all().at("msaa"), tsr::med::ParameterValue(std::int64_t{4}));
}

TEST(ClusterConfig, RejectsWhatCannotWork) {
  EXPECT_THROW(parseClusterConfig("{"), ConfigError);
  EXPECT_THROW(parseClusterConfig(R"({"mode": "spiral", "nodes": [{}]})"), ConfigError);
  EXPECT_THROW(parseClusterConfig(R"({"nodes": []})"), ConfigError);
  EXPECT_THROW(parseClusterConfig(R"({"mode": "tiled", "nodes": [{}], "wall": {"columns": 2, "rows": 2}})"),
               ConfigError);
  EXPECT_THROW(parseClusterConfig(R"({"nodes": [{"address": "nohost"}]})"), ConfigError);
  EXPECT_THROW(parseClusterConfig(R"({"nodes": [{"parameters": {"x": [1]}}]})"), ConfigError);
  // A misspelt key is refused, naming it and what the object takes.
  try {
    parseClusterConfig(R"({"nodes": [{}], "timeouts": {"lateMS": 5}})", "c.json");
    ADD_FAILURE() << "a misspelt key was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("c.json: unknown key 'lateMS' in 'timeouts' (it takes"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(parseClusterConfig(R"({"nodes": [{"adress": "127.0.0.1:1"}]})"), ConfigError);
  EXPECT_THROW(parseClusterConfig(R"({"nodes": [{}], "bogus": 1})"), ConfigError);
  // A scene's part size: KiB, 0 (the default) for a message's limit; beyond 1 GiB or negative refused.
  EXPECT_EQ(parseClusterConfig(R"({"nodes": [{}]})").snapshotPartBytes, 0u);
  EXPECT_EQ(parseClusterConfig(R"({"nodes": [{}], "snapshotPartKiB": 64})").snapshotPartBytes, 64u * 1024);
  EXPECT_THROW(parseClusterConfig(R"({"nodes": [{}], "snapshotPartKiB": -1})"), ConfigError);
  EXPECT_THROW(parseClusterConfig(R"({"nodes": [{}], "snapshotPartKiB": 1048577})"), ConfigError);
  EXPECT_THROW(parseClusterConfig(R"({"nodes": [{}], "snapshotPartKiB": "big"})"), ConfigError);
  // Screens: a count that differs from the nodes', no frame, a screen wholly outside, eyes on some only.
  const std::string two = R"({"mode": "tiled", "nodes": [{}, {}], "wall": )";
  EXPECT_THROW(parseClusterConfig(two + R"({"frame": [10, 10], "screens": [{"rect": [0, 0, 5, 5]}]}})"), ConfigError);
  EXPECT_THROW(parseClusterConfig(two + R"({"screens": [{"rect": [0, 0, 5, 5]}, {"rect": [5, 0, 5, 5]}]}})"),
               ConfigError);
  EXPECT_THROW(
      parseClusterConfig(two + R"({"frame": [10, 10], "screens": [{"rect": [0, 0, 5, 5]}, {"rect": [20, 0, 5, 5]}]}})"),
      ConfigError);
  EXPECT_THROW(parseClusterConfig(two + R"({"frame": [10, 10], "screens": [{"rect": [0, 0, 5, 5], "eye": "left"},
                                                                          {"rect": [5, 0, 5, 5]}]}})"),
               ConfigError);
  EXPECT_THROW(parseClusterConfig(two + R"({"frame": [10, 10], "screens": [{"rect": [0, 0, 4, 4], "bezel": 2},
                                                                          {"rect": [5, 0, 5, 5]}]}})"),
               ConfigError)
      << "a bezel that hides the whole screen";
}

// Non-uniform screens scale from the wall's frame to the rendered size; a
// negative bezel grows a screen (clipped to the frame).
TEST(WallLayout, ScreensScaleAndBezelsShrinkOrGrow) {
  ClusterConfig c =
      parseClusterConfig(R"({"mode": "tiled", "nodes": [{}, {}, {}], "wall": {"frame": [200, 100], "screens": [
      {"rect": [0, 0, 100, 100], "bezel": 10, "eye": "left"},
      {"rect": [100, 0, 100, 50], "bezel": -20, "eye": "right", "window": {"position": [-1920, 0], "fullscreen": true}},
      {"rect": [100, 50, 100, 50], "eye": "right"}]}})");
  auto screens = wallScreens(c.wall, 100, 50);
  ASSERT_EQ(screens.size(), 3u);
  EXPECT_EQ(screens[0].rect, (med::PixelRect{5, 5, 45, 45}));
  EXPECT_EQ(screens[1].rect, (med::PixelRect{40, 0, 100, 35}));
  EXPECT_EQ(screens[2].rect, (med::PixelRect{50, 25, 100, 50}));
  EXPECT_EQ(screens[0].eye, med::Eye::Left);
  EXPECT_EQ(screens[2].eye, med::Eye::Right);
  EXPECT_TRUE(c.wall.stereo());
  ASSERT_TRUE(c.wall.screens[1].window.has_value());
  EXPECT_EQ(c.wall.screens[1].window->x, -1920);
  EXPECT_TRUE(c.wall.screens[1].window->fullscreen);
}

}  // namespace
}  // namespace tsr::cluster

namespace tsr::cluster {
namespace {

TEST(ClusterConfig, ShippedConfigsParse) {
  for (const char* name : {"cooperative-2.json", "wall-2x2.json", "stereo-pair.json", "mixed-backends.json",
                           "wall-screens.json", "wall-stereo.json"}) {
    ClusterConfig c = loadClusterConfig(std::string(TSR_CONFIG_DIR) + "/" + name);
    EXPECT_FALSE(c.nodes.empty()) << name;
  }
  EXPECT_EQ(loadClusterConfig(std::string(TSR_CONFIG_DIR) + "/wall-2x2.json").mode, ClusterMode::Tiled);
  EXPECT_THROW(loadClusterConfig("/nonexistent.json"), ConfigError);
}

}  // namespace
}  // namespace tsr::cluster
