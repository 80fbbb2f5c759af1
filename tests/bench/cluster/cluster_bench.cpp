// cluster_bench: the cluster's numbers from one run, on loopback.
//   1. bytes on the wire per frame of builtin:animated (deltas) against its
//      snapshot, and bytes for one transform edit;
//   2. frame time of a 1-node loopback cluster against local rendering;
//   3. cooperative imbalance (max / mean node busy time) with the cost in
//      one corner of the image, after warm-up;
//   4. latency from commit() to "applied on all nodes" with 4 nodes.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <numeric>

#include <spdlog/spdlog.h>
#include <glm/gtc/matrix_transform.hpp>

#include "cluster_test_util.hpp"
#include "tsr/cluster/cluster_window.hpp"
#include "tsr/med/embree/register.hpp"
#include "tsr/med/image_file.hpp"
#include "tsr/sg/replica.hpp"
#include "tsr/sg/wire/wire_codec.hpp"

using namespace tsr;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

namespace {

double seconds(Clock::time_point since) { return std::chrono::duration<double>(Clock::now() - since).count(); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

std::uint64_t sent(const cluster::ClusterWindow& w) {
  std::uint64_t total = 0;
  for (const auto& s : w.status()) total += s.bytesSent;
  return total;
}

med::Parameters pathTracer(std::int64_t spp, std::int64_t threads) {
  med::Parameters p;
  p.set("spp", spp);
  p.set("maxDepth", std::int64_t{4});
  p.set("seed", std::int64_t{3});
  p.set("threads", threads);
  return p;
}

void wireBytes() {
  auto nodes = cluster::test::startNodes(1);
  cluster::ClusterWindow w(cluster::test::configFor(cluster::ClusterMode::Cooperative, nodes));
  w.connect(5s);
  cluster::test::AnimatedScene s;
  auto first = s.scene.commit();
  std::size_t snapshotBytes = sg::encode(*s.scene.snapshot()).size() + cluster::kFrameHeaderBytes;
  w.publish(s.scene, first);
  std::uint64_t before = sent(w);
  const int frames = 100;
  for (int f = 1; f <= frames; ++f) {
    s.pose(f);
    w.publish(s.scene, s.scene.commit());
  }
  double perFrame = double(sent(w) - before) / frames;
  // One transform edit: the first Transform the scene has.
  sg::Transform* t = nullptr;
  for (auto id : s.scene.ids())
    if ((t = s.scene.find<sg::Transform>(id))) break;
  sg::Mat4 m = t->matrix();
  m[3][0] += 0.5f;
  t->setMatrix(m);
  before = sent(w);
  w.publish(s.scene, s.scene.commit());
  std::uint64_t oneEdit = sent(w) - before;
  w.waitApplied(s.scene.version(), 5s);
  std::printf("wire: snapshot %zu bytes; animated delta %.1f bytes/frame (%.4f of the snapshot); one transform edit "
              "%llu bytes\n",
              snapshotBytes, perFrame, perFrame / double(snapshotBytes), static_cast<unsigned long long>(oneEdit));
}

void loopbackOverhead(std::uint32_t size, int frames) {
  auto nodes = cluster::test::startNodes(1);
  auto config = cluster::test::configFor(cluster::ClusterMode::Cooperative, nodes, pathTracer(4, 2));
  config.cooperative.tileSize = 64;
  cluster::ClusterWindow w(config);
  w.connect(5s);
  cluster::test::AnimatedScene s;
  w.setContent(s.imported.root, s.imported.background);
  sg::Replica replica;
  med::ViewportRegistry registry;
  med::registerEmbree(registry);
  med::ContextPool contexts;
  auto local = registry.create({"embree", s.imported.root, s.imported.background, pathTracer(4, 2), true}, contexts);
  std::vector<double> remote, here;
  for (int f = 0; f <= frames; ++f) {  // frame 0 converts the scene: not timed
    s.pose(f);
    auto delta = s.scene.commit();
    replica.apply(delta);
    const auto* cam = s.scene.find<sg::Camera>(s.imported.cameras.front());
    med::View view = med::View::fromCamera(*cam, size, size);
    auto t0 = Clock::now();
    med::FrameBuffer fb;
    local->render(replica, view, fb);
    double tl = seconds(t0);
    t0 = Clock::now();
    w.publish(s.scene, delta);
    auto frame = w.render(view);
    double tc = seconds(t0);
    if (!cluster::test::bitwiseEqual(frame.image, fb)) std::printf("  frame %d differs from the local render!\n", f);
    if (f > 0) {
      here.push_back(tl);
      remote.push_back(tc);
    }
  }
  std::printf("loopback: %ux%u spp 4, median local %.1f ms, 1-node cluster %.1f ms, ratio %.3f (target <= 1.10)\n",
              size, size, median(here) * 1e3, median(remote) * 1e3, median(remote) / median(here));
}

void cornerImbalance(int frames, float backOff, const std::string& imagePath, bool verbose) {
  const std::size_t n = 2;  // one per core: busy times are wall-clock
  auto nodes = cluster::test::startNodes(n);
  auto config = cluster::test::configFor(cluster::ClusterMode::Cooperative, nodes, pathTracer(8, 1));
  config.cooperative.tileSize = 16;
  config.cooperative.maxMovesPerFrame = 8;
  cluster::ClusterWindow w(config);
  w.connect(5s);
  cluster::test::AnimatedScene s("builtin:cornell");
  w.setContent(s.imported.root, s.imported.background);
  // Each frame nudges one transform by a hair: a new scene for the path
  // tracer (accumulation restarts everywhere), the same cost.
  sg::Transform* nudged = nullptr;
  for (auto id : s.scene.ids())
    if ((nudged = s.scene.find<sg::Transform>(id))) break;
  const auto* cam = s.scene.find<sg::Camera>(s.imported.cameras.front());
  // Step back from the box and shift the window: the box shrinks into the
  // top-left corner, the rest of the image looks past it at the cheap background.
  med::View view = med::View::fromCamera(*cam, 128, 128);
  view.cameraToWorld = view.cameraToWorld * glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, backOff));
  float hw = 0.5f * (view.right - view.left), hh = 0.5f * (view.top - view.bottom);
  view.left += 0.6f * hw;
  view.right += 0.6f * hw;
  view.bottom -= 0.6f * hh;
  view.top -= 0.6f * hh;
  if (!imagePath.empty()) {
    w.publish(s.scene, s.scene.commit());
    med::writeImage(imagePath, w.render(view).image);
  }
  std::vector<double> ratios, estimates;
  for (int f = 0; f < frames; ++f) {
    sg::Mat4 m = nudged->matrix();
    m[3][1] += (f % 2 ? -1e-4f : 1e-4f);
    nudged->setMatrix(m);
    w.publish(s.scene, s.scene.commit());
    auto frame = w.render(view);
    double max = *std::max_element(frame.busySeconds.begin(), frame.busySeconds.end());
    double mean = std::accumulate(frame.busySeconds.begin(), frame.busySeconds.end(), 0.0) / n;
    if (f == 0) std::printf("cooperative: first frame imbalance %.3f\n", max / mean);
    if (verbose)
      std::printf("  frame %d busy %.1f / %.1f ms, tiles %.1f / %.1f ms\n", f, frame.busySeconds[0] * 1e3,
                  frame.busySeconds[1] * 1e3, frame.tileSeconds[0] * 1e3, frame.tileSeconds[1] * 1e3);
    if (f >= frames / 2) {
      ratios.push_back(max / mean);
      estimates.push_back(w.estimatedImbalance());
    }
  }
  std::printf("cooperative: %zu nodes, 128x128, 16-px tiles, cost in one corner: imbalance after warm-up median %.3f "
              "(balancer's estimate %.3f; target <= 1.15)\n",
              n, median(ratios), median(estimates));
}

void replicationLatency(int frames) {
  auto nodes = cluster::test::startNodes(4);
  cluster::ClusterWindow w(cluster::test::configFor(cluster::ClusterMode::Cooperative, nodes));
  w.connect(5s);
  cluster::test::AnimatedScene s;
  w.publish(s.scene, s.scene.commit());
  w.waitApplied(s.scene.version(), 5s);
  std::vector<double> latency;
  for (int f = 1; f <= frames; ++f) {
    s.pose(f);
    auto t0 = Clock::now();
    auto delta = s.scene.commit();
    w.publish(s.scene, delta);
    if (!w.waitApplied(delta->version(), 5s)) std::printf("  frame %d not applied everywhere!\n", f);
    latency.push_back(seconds(t0));
  }
  std::sort(latency.begin(), latency.end());
  std::printf("latency: commit -> applied on 4 nodes, builtin:animated: median %.3f ms, p90 %.3f ms, max %.3f ms\n",
              latency[latency.size() / 2] * 1e3, latency[latency.size() * 9 / 10] * 1e3, latency.back() * 1e3);
}

}  // namespace

int main(int argc, char** argv) {
  spdlog::set_level(spdlog::level::warn);
  bool quick = argc > 1 && std::string(argv[1]) == "--quick";
  wireBytes();
  loopbackOverhead(quick ? 128 : 256, quick ? 5 : 10);
  cornerImbalance(quick ? 10 : 20, argc > 3 ? std::stof(argv[3]) : 3000.0f, argc > 2 ? argv[2] : "", argc > 4);
  replicationLatency(quick ? 50 : 200);
  return 0;
}
