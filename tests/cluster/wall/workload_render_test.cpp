// The workload of frames rendered on real nodes: the client's record of who
// rendered which tile covers the frame as the mode says, carries what the
// nodes report (their samples per pixel, rays), and the workload image the
// window draws matches it. The picture itself stays a local render's.
#include <gtest/gtest.h>

#include "cluster_test_util.hpp"
#include "tsr/cluster/cluster_window.hpp"
#include "tsr/cluster/wall_layout.hpp"
#include "tsr/med/embree/register.hpp"
#include "tsr/med/viewport_registry.hpp"
#include "tsr/sg/replica.hpp"
#include "wall/workload_check.hpp"

namespace tsr::cluster::test {
namespace {

using namespace std::chrono_literals;

med::Parameters pathTracer() {
  med::Parameters p;
  p.set("spp", std::int64_t{2});
  p.set("maxDepth", std::int64_t{3});
  p.set("seed", std::int64_t{7});
  p.set("threads", std::int64_t{1});
  return p;
}

ClientOptions withWorkload() {
  ClientOptions o;
  o.outputs = {std::string(kWorkloadOutput)};
  return o;
}

med::View viewOf(const AnimatedScene& s, std::uint32_t width, std::uint32_t height) {
  const sg::Camera* cam = s.imported.cameras.empty() ? nullptr : s.scene.find<sg::Camera>(s.imported.cameras.front());
  sg::Camera fallback;
  return med::View::fromCamera(cam ? *cam : fallback, width, height);
}

TEST(ClusterWorkload, CooperativeTilesCoverTheFrameOnceAndTheImageShowsTheirNodes) {
  auto nodes = startNodes(3);
  ClusterConfig c = configFor(ClusterMode::Cooperative, nodes, pathTracer());
  c.cooperative.tileSize = 16;
  c.cooperative.tolerance = 0.0;  // tiles move every frame: the record must follow
  AnimatedScene s("builtin:animated");
  ClusterWindow window(c, withWorkload());
  window.setContent(s.imported.root, s.imported.background);
  ASSERT_EQ(window.connect(5s), 3u);
  // The local reference: the nodes were not asked for the workload output.
  med::ViewportRegistry registry;
  med::registerEmbree(registry);
  med::ContextPool contexts;
  auto local = registry.create({"embree", s.imported.root, s.imported.background, pathTracer(), true}, contexts);
  sg::Replica replica;
  constexpr std::uint32_t kWidth = 72, kHeight = 40;  // edge tiles narrower than the rest
  for (int frame = 0; frame < 3; ++frame) {
    s.pose(frame * 6);
    auto delta = s.scene.commit();
    replica.apply(delta);
    window.publish(s.scene, delta);
    const med::View view = viewOf(s, kWidth, kHeight);
    ClusterFrame f = window.render(view);
    const std::string what = "frame " + std::to_string(frame);
    med::FrameBuffer reference;
    local->render(replica, view, reference);
    EXPECT_TRUE(bitwiseEqual(f.image, reference)) << what;
    EXPECT_EQ(f.participants, (std::vector<std::size_t>{0, 1, 2})) << what;
    EXPECT_EQ(f.tiles.size(), tileGrid(kWidth, kHeight, 16).size()) << what;
    expectCoveredExactlyOnce(f.tiles, kWidth, kHeight, what);
    for (const TileWork& t : f.tiles) {
      EXPECT_LT(t.node, 3u) << what;
      EXPECT_EQ(t.samples, 2u) << what << ": the nodes' samples per pixel";
      EXPECT_GT(t.rays, 0u) << what;
    }
    ASSERT_EQ(f.image.outputs.count(std::string(kWorkloadOutput)), 1u) << what;
    expectWorkloadImageMatches(f.image.outputs.at(std::string(kWorkloadOutput)), kWidth, kHeight, f.tiles, 3, what);
    const FrameWorkload& w = window.lastWorkload();
    std::uint64_t pixels = 0;
    for (const NodeWork& n : w.nodes) pixels += n.pixels;
    EXPECT_EQ(pixels, std::uint64_t{kWidth} * kHeight) << what;
    EXPECT_GE(w.balance, 1.0) << what;
    EXPECT_LE(w.balance, 3.0) << what;
  }
}

TEST(ClusterWorkload, WallScreensAreColouredByTheirNodesAndBezelsByNone) {
  auto nodes = startNodes(4);
  ClusterConfig c = configFor(ClusterMode::Tiled, nodes, pathTracer());
  c.wall.columns = 2;
  c.wall.rows = 2;
  c.wall.bezel = 4;
  AnimatedScene s("builtin:animated");
  ClusterWindow window(c, withWorkload());
  window.setContent(s.imported.root, s.imported.background);
  ASSERT_EQ(window.connect(5s), 4u);
  auto delta = s.scene.commit();
  window.publish(s.scene, delta);
  window.keepPixelsOnNodes(true);  // the record needs no pixels
  ClusterFrame f = window.render(viewOf(s, 48, 40));
  ASSERT_EQ(f.tiles.size(), 4u);
  const auto rects = wallLayout(48, 40, 2, 2, 4);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(f.tiles[i].node, i);
    EXPECT_EQ(f.tiles[i].rect, rects[i]);
  }
  const auto count = coverage(f.tiles, 48, 40);
  EXPECT_EQ(*std::max_element(count.begin(), count.end()), 1) << "screens overlap";
  expectWorkloadImageMatches(f.image.outputs.at(std::string(kWorkloadOutput)), 48, 40, f.tiles, 4, "wall");
}

TEST(ClusterWorkload, AStereoClusterHasNoWorkloadImage) {
  ClusterConfig c;
  c.mode = ClusterMode::Stereo;
  for (int port : {1, 2}) c.nodes.push_back({parseNodeAddress("127.0.0.1:" + std::to_string(port)), "embree", {}});
  EXPECT_THROW(ClusterWindow(c, withWorkload()), ClusterError);
  EXPECT_NO_THROW(ClusterWindow(c, ClientOptions{}));
}

}  // namespace
}  // namespace tsr::cluster::test
