// Rendering through real nodes with the Embree path tracer: with a fixed
// seed every mode, node count and fault is bitwise equal to a local render.
#include <filesystem>
#include <future>
#include <thread>

#include <regex>

#include <algorithm>

#include <gtest/gtest.h>

#include "cluster_test_util.hpp"
#include "protocol/raw_client.hpp"
#include "tsr/cluster/cluster_viewport.hpp"
#include "tsr/cluster/cluster_window.hpp"
#include "tsr/cluster/handshake.hpp"
#include "tsr/cluster/wall_layout.hpp"
#include "tsr/med/compositing.hpp"
#include "tsr/med/embree/register.hpp"
#include "tsr/med/image_file.hpp"
#include "tsr/med/viewport_registry.hpp"
#include "tsr/sg/replica.hpp"
#include "tsr/sg/wire/wire_codec.hpp"

namespace tsr::cluster::test {
namespace {

using namespace std::chrono_literals;
constexpr std::uint32_t kSize = 64;

med::Parameters pathTracer(std::int64_t spp = 2) {
  med::Parameters p;
  p.set("spp", spp);
  p.set("maxDepth", std::int64_t{3});
  p.set("seed", std::int64_t{7});
  p.set("threads", std::int64_t{1});
  return p;
}

// The application's side: the scene, a local replica and a local viewport
// for the reference image, and the cluster window.
struct Session {
  AnimatedScene s;
  sg::Replica replica;
  med::ViewportRegistry registry;
  med::ContextPool contexts;
  std::unique_ptr<med::Viewport> local;
  std::unique_ptr<ClusterWindow> window;

  Session(const std::string& scene, ClusterConfig config, med::Parameters parameters) : s(scene) {
    med::registerEmbree(registry);
    med::ViewportSettings vs{"embree", s.imported.root, s.imported.background, std::move(parameters), true};
    local = registry.create(vs, contexts);
    window = std::make_unique<ClusterWindow>(std::move(config));
    window->setContent(s.imported.root, s.imported.background);
  }
  std::size_t connect() { return window->connect(5s); }
  void publish(int frame = -1) {
    if (frame >= 0) s.pose(frame);
    auto delta = s.scene.commit();
    replica.apply(delta);
    window->publish(s.scene, delta);
  }
  med::View view() const {
    const sg::Camera* cam = nullptr;
    if (!s.imported.cameras.empty()) cam = s.scene.find<sg::Camera>(s.imported.cameras.front());
    sg::Camera fallback;
    return med::View::fromCamera(cam ? *cam : fallback, kSize, kSize);
  }
  med::FrameBuffer reference(const med::View& v) {
    med::FrameBuffer fb;
    local->render(replica, v, fb);
    return fb;
  }
  // Left and right eye rendered by two local viewports, as a local stereo window would.
  std::pair<med::FrameBuffer, med::FrameBuffer> eyes(float separation, float zeroParallax) {
    auto right = registry.create({"embree", s.imported.root, s.imported.background, local->settings().parameters, true},
                                 contexts);
    med::FrameBuffer l, r;
    local->render(replica, view().eye(med::Eye::Left, separation, zeroParallax), l);
    right->render(replica, view().eye(med::Eye::Right, separation, zeroParallax), r);
    return {std::move(l), std::move(r)};
  }
};

TEST(ClusterRender, CooperativeOnThreeNodesEqualsLocal) {
  auto nodes = startNodes(3);
  ClusterConfig c = configFor(ClusterMode::Cooperative, nodes, pathTracer());
  c.cooperative.tileSize = 16;
  Session app("builtin:cornell", c, pathTracer());
  ASSERT_EQ(app.connect(), 3u);
  app.publish();
  ClusterFrame f = app.window->render(app.view());
  EXPECT_TRUE(bitwiseEqual(f.image, app.reference(app.view())));
  for (std::size_t n = 0; n < 3; ++n) EXPECT_GT(f.busySeconds[n], 0.0) << "node " << n << " did no work";
}

// While the nodes work, the window reports each tile's arrival as the
// share of the frame done: rising, one call a tile, ending at 1.
TEST(ClusterRender, ProgressRisesWithEachTile) {
  auto nodes = startNodes(2);
  ClusterConfig c = configFor(ClusterMode::Cooperative, nodes, pathTracer(1));
  c.cooperative.tileSize = 16;
  Session app("builtin:cornell", c, pathTracer(1));
  ASSERT_EQ(app.connect(), 2u);
  app.publish();
  std::vector<double> shares;
  app.window->setProgress([&](double share) { shares.push_back(share); });
  const ClusterFrame f = app.window->render(app.view());
  ASSERT_EQ(shares.size(), f.tiles.size());
  EXPECT_TRUE(std::is_sorted(shares.begin(), shares.end()));
  EXPECT_GT(shares.front(), 0.0);
  EXPECT_EQ(shares.back(), 1.0);
}

TEST(ClusterRender, AnimatedCooperativeFramesStayEqualWhileTilesMove) {
  auto nodes = startNodes(2);
  ClusterConfig c = configFor(ClusterMode::Cooperative, nodes, pathTracer(1));
  c.cooperative.tileSize = 16;
  c.cooperative.tolerance = 0.0;  // move tiles every frame: pixels must not care
  Session app("builtin:animated", c, pathTracer(1));
  ASSERT_EQ(app.connect(), 2u);
  for (int frame = 0; frame < 4; ++frame) {
    app.publish(frame * 6);
    ClusterFrame f = app.window->render(app.view());
    EXPECT_TRUE(bitwiseEqual(f.image, app.reference(app.view()))) << "frame " << frame;
  }
}

// A ClusterViewport is a layer like a local viewport: it catches the nodes
// up from the replica (a snapshot, then single deltas) and renders regions.
TEST(ClusterRender, ClusterViewportFollowsTheReplicaAndRendersRegions) {
  auto nodes = startNodes(2);
  ClusterConfig c = configFor(ClusterMode::Cooperative, nodes, pathTracer(1));
  c.cooperative.tileSize = 16;
  Session app("builtin:animated", c, pathTracer(1));
  ASSERT_EQ(app.connect(), 2u);
  ClusterViewport viewport({"embree", app.s.imported.root, app.s.imported.background, pathTracer(1), true},
                           std::move(app.window), {});
  for (int frame = 0; frame < 3; ++frame) {
    app.s.pose(frame * 6);
    app.replica.apply(app.s.scene.commit());
    med::FrameBuffer image;
    const auto stats = viewport.render(app.replica, app.view(), image);
    EXPECT_EQ(stats.update, frame == 0 ? med::SceneAdapter::Update::Converted : med::SceneAdapter::Update::Synced);
    EXPECT_TRUE(bitwiseEqual(image, app.reference(app.view()))) << "frame " << frame;
  }
  const med::View tile = app.view().cropped({8, 16, 40, 48});
  med::FrameBuffer part;
  EXPECT_EQ(viewport.render(app.replica, tile, part).update, med::SceneAdapter::Update::None);
  EXPECT_TRUE(bitwiseEqual(part, app.reference(tile)));
}

TEST(ClusterRender, WallTwoByTwoStitchedEqualsLocal) {
  auto nodes = startNodes(4);
  ClusterConfig c = configFor(ClusterMode::Tiled, nodes, pathTracer());
  Session app("builtin:cornell", c, pathTracer());
  ASSERT_EQ(app.connect(), 4u);
  app.publish();
  ClusterFrame f = app.window->render(app.view());
  EXPECT_EQ(f.offlineTiles, 0u);
  EXPECT_TRUE(bitwiseEqual(f.image, app.reference(app.view())));
}

TEST(ClusterRender, WallBezelsHidePixelsButTilesStillMatch) {
  auto nodes = startNodes(4);
  ClusterConfig c = configFor(ClusterMode::Tiled, nodes, pathTracer());
  c.wall.bezel = 6;
  Session app("builtin:cornell", c, pathTracer());
  ASSERT_EQ(app.connect(), 4u);
  app.publish();
  ClusterFrame f = app.window->render(app.view());
  med::FrameBuffer ref = app.reference(app.view());
  for (const auto& r : wallLayout(kSize, kSize, 2, 2, 6))
    for (std::uint32_t y = r.y0; y < r.y1; ++y)
      for (std::uint32_t x = r.x0; x < r.x1; ++x)
        ASSERT_EQ(f.image.colour[f.image.index(x, y)], ref.colour[ref.index(x, y)]);
  EXPECT_EQ(f.image.colour[f.image.index(32, 5)], glm::vec4(0.0f)) << "bezel pixels are not rendered";
}

TEST(ClusterRender, WallNeverStallsOnANodeThatStopsAnswering) {
  auto nodes = startNodes(4);
  ClusterConfig c = configFor(ClusterMode::Tiled, nodes, pathTracer(1));
  c.timeouts.deadAfter = 800ms;
  c.timeouts.heartbeat = 100ms;
  Session app("builtin:cornell", c, pathTracer(1));
  ASSERT_EQ(app.connect(), 4u);
  app.publish();
  med::FrameBuffer ref = app.reference(app.view());
  nodes[3]->pause();
  // Liveness, not a stopwatch: frames keep coming while the node is silent,
  // each with its tile as offline fill and the others rendered.
  auto tile = wallLayout(kSize, kSize, 2, 2, 0)[3];
  std::uint64_t last = 0;
  for (int frame = 0; frame < 3; ++frame) {
    ClusterFrame f = app.window->render(app.view());
    EXPECT_GT(f.frame, last) << "frame " << frame;
    last = f.frame;
    EXPECT_EQ(f.offlineTiles, 1u);
    EXPECT_EQ(f.image.colour[f.image.index(tile.x0 + 1, tile.y0 + 1)], c.wall.offlineColour);
    EXPECT_EQ(f.image.colour[f.image.index(1, 1)], ref.colour[ref.index(1, 1)]);
  }
  // Back: it reconnects, receives a snapshot, and its tile is right again.
  nodes[3]->resume();
  ClusterFrame again;
  for (int attempt = 0; attempt < 50; ++attempt) {
    std::this_thread::sleep_for(100ms);
    app.publish();
    ref = app.reference(app.view());
    again = app.window->render(app.view());
    if (again.offlineTiles == 0) break;
  }
  EXPECT_EQ(again.offlineTiles, 0u);
  EXPECT_TRUE(bitwiseEqual(again.image, ref));
}

// A late node is named with the phase it is stuck in and since when, while
// the frame waits for it: behind on the scene (snapshot), or rendering.
TEST(ClusterRender, ALateNodeIsNamedWithItsPhaseAndSince) {
  auto nodes = startNodes(2);
  ClusterConfig c = configFor(ClusterMode::Tiled, nodes, pathTracer(1));
  c.wall.columns = 2;
  c.wall.rows = 1;
  c.timeouts.late = 150ms;
  c.timeouts.heartbeat = 100ms;
  c.timeouts.deadAfter = 1500ms;
  Session app("builtin:animated", c, pathTracer(1));
  ASSERT_EQ(app.connect(), 2u);
  app.publish(0);
  app.window->render(app.view());
  const std::regex line(R"(127\.0\.0\.1:\d+ \(node\): (snapshot|render) since \d\d:\d\d:\d\d\.\d{3} \(\d+ ms\))");
  auto reportFor = [](const ClusterFrame& f, const NodeProcess& n) {
    std::string found;
    for (const auto& l : f.lateNodes)
      if (l.rfind(n.text() + " ", 0) == 0) found = l;
    return found;
  };

  nodes[1]->pause();  // it cannot apply the next change list
  app.publish(1);
  ClusterFrame behind = app.window->render(app.view());
  nodes[1]->resume();
  std::string said = reportFor(behind, *nodes[1]);
  EXPECT_TRUE(std::regex_match(said, line)) << said;
  EXPECT_NE(said.find("snapshot since"), std::string::npos) << said;
  EXPECT_EQ(behind.offlineTiles, 1u) << "lost after the dead-node timeout";

  app.publish(2);
  ASSERT_TRUE(app.window->waitApplied(app.s.scene.version(), 5s));
  nodes[0]->pause();  // it has the scene, but renders nothing
  ClusterFrame stuck = app.window->render(app.view());
  nodes[0]->resume();
  said = reportFor(stuck, *nodes[0]);
  EXPECT_TRUE(std::regex_match(said, line)) << said;
  EXPECT_NE(said.find("render since"), std::string::npos) << said;
}

TEST(ClusterRender, WallNodesPresentTheirTilesWhenTheBarrierReleases) {
  char dirName[] = "/tmp/tsr-present-XXXXXX";
  std::string dir = mkdtemp(dirName);
  std::vector<std::unique_ptr<NodeProcess>> nodes;
  for (int i = 0; i < 4; ++i)
    nodes.push_back(std::make_unique<NodeProcess>(
        std::vector<std::string>{"--present", "files:" + dir, "--name", "n" + std::to_string(i)}));
  Session app("builtin:cornell", configFor(ClusterMode::Tiled, nodes, pathTracer()), pathTracer());
  ASSERT_EQ(app.connect(), 4u);
  app.publish();
  ClusterFrame f = app.window->render(app.view());
  med::FrameBuffer ref = app.reference(app.view());
  auto rects = wallLayout(kSize, kSize, 2, 2, 0);
  for (int i = 0; i < 4; ++i) {
    std::string path = dir + "/n" + std::to_string(i) + "-frame" + std::to_string(f.frame) + "-" +
                       std::to_string(rects[i].x0) + "-" + std::to_string(rects[i].y0) + ".exr";
    for (int wait = 0; wait < 500 && access(path.c_str(), R_OK) != 0; ++wait) std::this_thread::sleep_for(20ms);
    med::FrameBuffer shown = med::readImage(path);
    ASSERT_EQ(shown.width, rects[i].width());
    for (std::uint32_t y = 0; y < shown.height; ++y)
      for (std::uint32_t x = 0; x < shown.width; ++x)
        ASSERT_EQ(shown.colour[shown.index(x, y)], ref.colour[ref.index(rects[i].x0 + x, rects[i].y0 + y)]) << path;
  }
  std::filesystem::remove_all(dir);
}

TEST(ClusterRender, RestartedNodeRejoinsAndRendersIdenticalPixels) {
  auto nodes = startNodes(2);
  ClusterConfig c = configFor(ClusterMode::Cooperative, nodes, pathTracer());
  c.cooperative.tileSize = 16;
  c.cooperative.maxMovesPerFrame = 16;
  Session app("builtin:animated", c, pathTracer());
  ASSERT_EQ(app.connect(), 2u);
  app.publish(0);
  ASSERT_TRUE(bitwiseEqual(app.window->render(app.view()).image, app.reference(app.view())));
  std::string address = nodes[1]->text();
  nodes[1]->kill();
  app.publish(1);
  ClusterFrame alone = app.window->render(app.view());  // node 0 alone
  EXPECT_TRUE(bitwiseEqual(alone.image, app.reference(app.view())));
  nodes[1] = std::make_unique<NodeProcess>(std::vector<std::string>{}, address);
  ClusterFrame back;
  for (int frame = 2; frame < 40; ++frame) {
    std::this_thread::sleep_for(50ms);
    app.publish(frame);
    back = app.window->render(app.view());
    ASSERT_TRUE(bitwiseEqual(back.image, app.reference(app.view()))) << "frame " << frame;
    if (back.busySeconds[1] > 0) break;
  }
  EXPECT_GT(back.busySeconds[1], 0.0) << "the restarted node takes part again";
}

TEST(ClusterRender, StereoPairComposedEqualsLocalComposition) {
  auto nodes = startNodes(2);
  ClusterConfig c = configFor(ClusterMode::Stereo, nodes, pathTracer());
  Session app("builtin:cornell", c, pathTracer());
  app.window->setEyes(0.1f, 3.0f);
  ASSERT_EQ(app.connect(), 2u);
  app.publish();
  ClusterFrame f = app.window->render(app.view());
  const auto [l, r] = app.eyes(0.1f, 3.0f);
  EXPECT_TRUE(bitwiseEqual(f.left, l));
  EXPECT_TRUE(bitwiseEqual(f.right, r));
  EXPECT_TRUE(bitwiseEqual(f.image, med::anaglyph(l, r)));
  EXPECT_FALSE(bitwiseEqual(l, r)) << "the eyes must differ";
  EXPECT_GT(f.busySeconds[0], 0.0);
  EXPECT_GT(f.busySeconds[1], 0.0);
}

// A stereo wall is one config: each screen names its eye. Two screens per
// eye, side by side, stitch to the local left and right eye renders.
TEST(ClusterRender, StereoWallInOneConfigEqualsLocalEyes) {
  auto nodes = startNodes(4);
  ClusterConfig c = configFor(ClusterMode::Tiled, nodes, pathTracer());
  c.wall.frameWidth = c.wall.frameHeight = kSize;
  const std::uint32_t half = kSize / 2;
  for (med::Eye eye : {med::Eye::Left, med::Eye::Right})
    for (std::int32_t x : {0, static_cast<std::int32_t>(half)})
      c.wall.screens.push_back({x, 0, half, kSize, 0, eye, {}});
  c.stereo.compose = StereoCompose::Anaglyph;
  Session app("builtin:cornell", c, pathTracer());
  app.window->setEyes(0.1f, 3.0f);
  ASSERT_EQ(app.connect(), 4u);
  app.publish();
  ClusterFrame f = app.window->render(app.view());
  EXPECT_EQ(f.offlineTiles, 0u);
  const auto [l, r] = app.eyes(0.1f, 3.0f);
  EXPECT_TRUE(bitwiseEqual(f.left, l));
  EXPECT_TRUE(bitwiseEqual(f.right, r));
  EXPECT_TRUE(bitwiseEqual(f.image, med::anaglyph(l, r)));
  for (std::size_t i = 0; i < 4; ++i) EXPECT_GT(f.busySeconds[i], 0.0) << "screen " << i;
}

TEST(ClusterRender, KilledNodesTilesAreTakenOverAndTheImageStaysEqual) {
  auto nodes = startNodes(3);
  ClusterConfig c = configFor(ClusterMode::Cooperative, nodes, pathTracer(8));
  c.cooperative.tileSize = 8;
  Session app("builtin:animated", c, pathTracer(8));
  ASSERT_EQ(app.connect(), 3u);
  app.publish(0);
  med::FrameBuffer ref = app.reference(app.view());
  ASSERT_TRUE(bitwiseEqual(app.window->render(app.view()).image, ref));
  // Kill one node while the next frame renders (the scene changes, so no tile is cached).
  app.publish(3);
  ref = app.reference(app.view());
  // Paused, the node holds its tiles for sure when it dies.
  nodes[1]->pause();
  auto frame = std::async(std::launch::async, [&] { return app.window->render(app.view()); });
  std::this_thread::sleep_for(200ms);
  nodes[1]->kill();
  ClusterFrame f = frame.get();
  EXPECT_TRUE(bitwiseEqual(f.image, ref));
  EXPECT_GT(f.reassignedItems, 0u) << "the dead node's tiles were taken over within the frame";
  // And the frames after it, on the two left.
  app.publish(4);
  ClusterFrame next = app.window->render(app.view());
  EXPECT_TRUE(bitwiseEqual(next.image, app.reference(app.view())));
  EXPECT_EQ(next.busySeconds[1], 0.0);
}

TEST(ClusterRender, LateJoinerTakesPartAndMatches) {
  auto nodes = startNodes(1);
  ClusterConfig c = configFor(ClusterMode::Cooperative, nodes, pathTracer());
  c.cooperative.tileSize = 16;
  c.cooperative.maxMovesPerFrame = 16;
  Session app("builtin:cornell", c, pathTracer());
  ASSERT_EQ(app.connect(), 1u);
  app.publish();
  app.window->render(app.view());
  NodeProcess late;
  app.window->addNode({late.address(), "embree", pathTracer()});
  for (int i = 0; i < 50 && app.window->status()[1].state != NodeState::Synced; ++i) {
    std::this_thread::sleep_for(20ms);
    app.publish();
  }
  ASSERT_EQ(app.window->status()[1].state, NodeState::Synced);
  app.window->render(app.view());  // measures; the balancer hands the joiner tiles for the next frame
  ClusterFrame f = app.window->render(app.view());
  EXPECT_GT(f.busySeconds[1], 0.0);
  EXPECT_TRUE(bitwiseEqual(f.image, app.reference(app.view())));
}

// Found by replaying recorded traffic with mutations: a RenderRequest whose
// eye is at -2.7e38 (finite) passed every check and aborted the node inside
// Embree, for all its clients. That client now gets an error; the node
// renders the next client's frame exactly as before.
TEST(ClusterRender, EyeBeyondTheCoordinateLimitIsRefusedAndTheNodeServesOn) {
  auto nodes = startNodes(1);
  Session app("builtin:cornell", configFor(ClusterMode::Cooperative, nodes, pathTracer(1)), pathTracer(1));
  ASSERT_EQ(app.connect(), 1u);
  app.publish();
  const med::FrameBuffer before = app.window->render(app.view()).image;
  ASSERT_TRUE(bitwiseEqual(before, app.reference(app.view())));

  for (float eye : {-2.7e38f, 1e20f, 2e12f}) {
    // An authenticated client with a scene and a viewport, as a real one has.
    RawClient raw(nodes[0]->address());
    ClientHandshake hs("", "mutated replay");
    ASSERT_TRUE(raw.send(hs.hello()));
    Message m;
    ASSERT_EQ(raw.read(m), RawClient::Outcome::Message);
    ASSERT_TRUE(raw.send(hs.onChallenge(m)));
    ASSERT_EQ(raw.read(m), RawClient::Outcome::Message);
    ASSERT_EQ(m.type, Welcome::kType);
    ASSERT_TRUE(raw.send(frameFromPayload(Snapshot::kType, sg::encode(*app.s.scene.snapshot()))));
    ASSERT_EQ(raw.read(m), RawClient::Outcome::Message);
    ASSERT_EQ(m.type, Applied::kType);
    ASSERT_TRUE(raw.send(
        makeFrame(SetViewports{{{0, "embree", app.s.imported.root, app.s.imported.background, pathTracer(1)}}})));

    med::View view = app.view();
    view.cameraToWorld[3][2] = eye;
    RenderRequest request;
    request.frame = 1;
    request.jobs.push_back({0, view, {view.region}});
    // The codec's writer does not validate: bytes as an attacker sends them.
    ASSERT_TRUE(raw.send(makeFrame(request)));
    ASSERT_EQ(raw.read(m), RawClient::Outcome::Message) << "eye " << eye;
    ASSERT_EQ(m.type, ErrorReport::kType) << "eye " << eye;
    EXPECT_EQ(parse<ErrorReport>(m).kind, ErrorReport::Kind::ProtocolViolation);
    EXPECT_NE(parse<ErrorReport>(m).reason.find("beyond the coordinate limit"), std::string::npos)
        << parse<ErrorReport>(m).reason;
    EXPECT_EQ(raw.waitClosed(), RawClient::Outcome::Closed);

    EXPECT_TRUE(nodes[0]->alive());
    const ClusterFrame after = app.window->render(app.view());
    EXPECT_EQ(after.offlineTiles, 0u);
    EXPECT_TRUE(bitwiseEqual(after.image, before)) << "after eye " << eye;
  }
}

}  // namespace
}  // namespace tsr::cluster::test
