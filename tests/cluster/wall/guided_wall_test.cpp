// visibility=guided on real tessera-node processes running the Vulkan
// back-end: every tile of a 2x2 wall, and each eye of a stereo pair on two
// nodes, equals the same view rendered locally with visibility=all, bit for
// bit, frame after frame and while the camera moves.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "cluster_test_util.hpp"
#include "tsr/cluster/cluster_window.hpp"
#include "tsr/cluster/wall_layout.hpp"
#include "tsr/med/viewport_registry.hpp"
#include "tsr/med/vulkan/register.hpp"
#if TSR_GUIDED_BOUNCED_LIGHT
#include "tsr/med/embree/register.hpp"
#endif
#include "tsr/sg/replica.hpp"

namespace tsr::cluster::test {
namespace {

using namespace std::chrono_literals;
constexpr std::uint32_t kWidth = 96, kHeight = 64;

// A small plant published to `nodeCount` real nodes rendering Vulkan with
// visibility=guided in `mode`, and a registry for the local full draws.
struct GuidedCluster {
  std::vector<std::unique_ptr<NodeProcess>> nodes;
  AnimatedScene s{"builtin:plant:20000"};
  sg::Replica replica;
  med::ViewportRegistry registry;
  med::ContextPool contexts;
  std::unique_ptr<ClusterWindow> window;

  GuidedCluster(ClusterMode mode, std::size_t nodeCount, float eyeSeparation = 0.0f) : nodes(startNodes(nodeCount)) {
    med::Parameters guided;
    guided.set("visibility", std::string("guided"));
    ClusterConfig c = configFor(mode, nodes, guided);
    for (auto& n : c.nodes) n.backend = "vulkan";
    med::registerVulkan(registry);
#if TSR_GUIDED_BOUNCED_LIGHT
    // Nodes light the rasterizer with the path tracer's probes, each tracing
    // its own: the local draw traces them too, and must come out the same.
    med::registerEmbree(registry);
#endif
    window = std::make_unique<ClusterWindow>(std::move(c));
    window->setContent(s.imported.root, s.imported.background);
    if (eyeSeparation > 0.0f) window->setEyes(eyeSeparation, 5.0f);
    EXPECT_EQ(window->connect(5s), nodeCount);
    auto delta = s.scene.commit();
    replica.apply(delta);
    window->publish(s.scene, delta);
  }
  // A local viewport drawing everything (visibility=all).
  std::unique_ptr<med::Viewport> fullDraw() {
    return registry.create({"vulkan", s.imported.root, s.imported.background, {}, true}, contexts);
  }
  med::View view() const {
    return med::View::fromCamera(*s.scene.find<sg::Camera>(s.imported.cameras.front()), kWidth, kHeight);
  }
};

TEST(ClusterGuided, WallTilesGuidedEqualLocalFullDraw) {
  GuidedCluster cluster(ClusterMode::Tiled, 4);
  auto local = cluster.fullDraw();
  med::View view = cluster.view();
  for (int frame = 0; frame < 4; ++frame) {
    if (frame == 3)  // a step along the aisle
      view.cameraToWorld = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 4)) * view.cameraToWorld;
    ClusterFrame f = cluster.window->render(view);
    ASSERT_EQ(f.offlineTiles, 0u);
    for (const auto& r : wallLayout(kWidth, kHeight, 2, 2, 0)) {
      med::FrameBuffer tile;
      local->render(cluster.replica, view.cropped(r), tile);
      std::size_t differ = 0;
      for (std::uint32_t y = r.y0; y < r.y1; ++y)
        for (std::uint32_t x = r.x0; x < r.x1; ++x)
          differ += f.image.colour[f.image.index(x, y)] != tile.colour[tile.index(x - r.x0, y - r.y0)];
      EXPECT_EQ(differ, 0u) << "frame " << frame << ", tile at " << r.x0 << "," << r.y0;
    }
  }
}

TEST(ClusterGuided, StereoEyesOnTwoNodesGuidedEqualLocalFullDraw) {
  GuidedCluster cluster(ClusterMode::Stereo, 2, 0.065f);
  auto left = cluster.fullDraw();
  auto right = cluster.fullDraw();
  const med::View view = cluster.view();
  for (int frame = 0; frame < 3; ++frame) {
    ClusterFrame f = cluster.window->render(view);
    med::FrameBuffer l, r;
    left->render(cluster.replica, view.eye(med::Eye::Left, 0.065f, 5.0f), l);
    right->render(cluster.replica, view.eye(med::Eye::Right, 0.065f, 5.0f), r);
    EXPECT_TRUE(bitwiseEqual(f.left, l)) << "frame " << frame;
    EXPECT_TRUE(bitwiseEqual(f.right, r)) << "frame " << frame;
    EXPECT_FALSE(bitwiseEqual(l, r)) << "the eyes must differ";
  }
}

}  // namespace
}  // namespace tsr::cluster::test
