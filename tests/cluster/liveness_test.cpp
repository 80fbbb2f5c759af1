// Bulk is not silence: a snapshot and a tile that take several times the
// dead-node timeout to cross a throttled link leave the node counted alive.
#include <gtest/gtest.h>

#include "cluster_test_util.hpp"
#include "protocol/loopback_proxy.hpp"
#include "tsr/cluster/cluster_window.hpp"
#include "tsr/med/embree/register.hpp"
#include "tsr/sg/geometry.hpp"
#include "tsr/sg/replica.hpp"
#include "tsr/sg/wire/wire_codec.hpp"

namespace tsr::cluster::test {
namespace {

using namespace std::chrono_literals;

TEST(ClusterLiveness, SlowSnapshotAndTileDoNotCountAsADeadNode) {
  NodeProcess node;
  constexpr std::size_t kRate = 1 << 20;  // 1 MiB/s each way
  LoopbackProxy proxy(node.address());
  proxy.setRate(kRate);
  proxy.setSocketBuffers(16 * 1024);

  AnimatedScene s("builtin:cornell");
  // Ballast no viewport shows (it hangs under no root): 4 MiB of points.
  s.scene.create<sg::Geometry>().setPositions(std::vector<sg::Vec3>(350000, sg::Vec3(1.0f, 2.0f, 3.0f)));
  auto delta = s.scene.commit();
  const std::size_t snapshotBytes = sg::encode(*s.scene.snapshot()).size();
  sg::Replica replica;
  replica.apply(delta);

  med::Parameters p;
  p.set("spp", std::int64_t{1});
  p.set("seed", std::int64_t{3});
  p.set("threads", std::int64_t{1});
  ClusterConfig c;
  c.mode = ClusterMode::Cooperative;
  c.compression = Compression::None;  // the tile crosses the link at full size
  c.cooperative.tileSize = 256;
  c.nodes.push_back({proxy.address(), "embree", p});
  c.timeouts.heartbeat = 100ms;
  c.timeouts.deadAfter = 600ms;
  c.timeouts.frame = 60000ms;
  const auto timeout = c.timeouts.deadAfter;
  ClusterWindow window(c);
  window.setContent(s.imported.root, s.imported.background);
  ASSERT_EQ(window.connect(5s), 1u);

  // The snapshot takes seconds on this link: five times the timeout at least.
  ASSERT_GT(snapshotBytes, 5 * kRate * timeout.count() / 1000);
  window.publish(s.scene, delta);
  ASSERT_TRUE(window.waitApplied(s.scene.version(), 60s)) << window.status()[0].lastError;
  EXPECT_EQ(window.status()[0].state, NodeState::Synced);
  EXPECT_EQ(window.status()[0].lastError, "");

  // One 256x256 tile, uncompressed (about 1.3 MB): twice the timeout on the way back.
  const sg::Camera* cam = s.scene.find<sg::Camera>(s.imported.cameras.front());
  med::View view = med::View::fromCamera(*cam, 256, 256);
  ClusterFrame f = window.render(view);
  EXPECT_EQ(window.status()[0].state, NodeState::Synced) << window.status()[0].lastError;
  EXPECT_EQ(window.status()[0].lastError, "");
  EXPECT_GT(f.busySeconds[0], 0.0);

  med::ViewportRegistry registry;
  med::registerEmbree(registry);
  med::ContextPool contexts;
  auto local = registry.create({"embree", s.imported.root, s.imported.background, p, true}, contexts);
  med::FrameBuffer ref;
  local->render(replica, view, ref);
  EXPECT_TRUE(bitwiseEqual(f.image, ref));
}

}  // namespace
}  // namespace tsr::cluster::test
