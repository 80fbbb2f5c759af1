// guided_wall_compare: visibility=all against visibility=guided on a 2x2
// wall of tessera-node processes on loopback, each running the Vulkan
// back-end on its tile. A comparison program, not a timed test:
//   guided_wall_compare [SCENE] [WIDTHxHEIGHT] [FRAMES]
// (default builtin:plant:5000000 960x540 3). Per view: the median wall
// frame time (client wall clock, tiles back to the client), the slowest
// node's median tile time, and the pixels of the stitched frame that differ
// between the modes on the last still frame.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>

#include <spdlog/spdlog.h>
#include <glm/gtc/matrix_transform.hpp>

#include "cluster_test_util.hpp"
#include "tsr/cluster/cluster_window.hpp"

using namespace tsr;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

struct Result {
  double frame = 0, slowestTile = 0;
  med::FrameBuffer image;
};

med::View looking(med::View v, glm::vec3 eye, glm::vec3 target) {
  v.cameraToWorld = glm::inverse(glm::lookAt(eye, target, glm::vec3(0, 1, 0)));
  return v;
}

// One wall of four fresh nodes in `mode`, every view `frames` still frames after one to learn.
std::vector<Result> play(const std::string& scene, const std::string& mode, const std::vector<med::View>& views,
                         int frames) {
  auto nodes = cluster::test::startNodes(4);
  med::Parameters p;
  p.set("visibility", mode);
  cluster::ClusterConfig c = cluster::test::configFor(cluster::ClusterMode::Tiled, nodes, p);
  for (auto& n : c.nodes) n.backend = "vulkan";
  c.timeouts.frame = std::chrono::milliseconds(600000);
  c.timeouts.connect = std::chrono::milliseconds(10000);
  cluster::test::AnimatedScene s(scene);
  cluster::ClusterWindow window(std::move(c));
  window.setContent(s.imported.root, s.imported.background);
  if (window.connect(10s) != 4) throw std::runtime_error("not all four nodes connected");
  window.publish(s.scene, s.scene.commit());
  std::vector<Result> out;
  for (const med::View& v : views) {
    window.render(v);  // the nodes convert the scene on the first; guided learns what is visible
    std::vector<double> frame, tile;
    Result r;
    for (int i = 0; i < frames; ++i) {
      const auto start = Clock::now();
      cluster::ClusterFrame f = window.render(v);
      frame.push_back(std::chrono::duration<double>(Clock::now() - start).count());
      tile.push_back(*std::max_element(f.tileSeconds.begin(), f.tileSeconds.end()));
      r.image = std::move(f.image);
    }
    r.frame = median(frame);
    r.slowestTile = median(tile);
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  spdlog::set_level(spdlog::level::warn);
  const std::string scene = argc > 1 ? argv[1] : "builtin:plant:5000000";
  std::uint32_t width = 960, height = 540;
  if (argc > 2 && std::sscanf(argv[2], "%ux%u", &width, &height) != 2) return std::fprintf(stderr, "bad size\n"), 2;
  const int frames = argc > 3 ? std::max(1, std::atoi(argv[3])) : 3;

  cluster::test::AnimatedScene s(scene);
  const med::View inside = med::View::fromCamera(*s.scene.find<sg::Camera>(s.imported.cameras.front()), width, height);
  const glm::vec3 eye(inside.cameraToWorld[3]);
  const std::vector<med::View> views = {inside, looking(inside, eye + glm::vec3(0, 0, 30), eye + glm::vec3(10, 0, 36)),
                                        looking(inside, eye + glm::vec3(-60, 40, -40), eye + glm::vec3(0, 0, 60))};
  const char* names[] = {"inside, down the aisle", "inside, turned", "outside, above a corner"};
  const std::vector<Result> all = play(scene, "all", views, frames);
  const std::vector<Result> guided = play(scene, "guided", views, frames);
  std::printf("%s on a 2x2 loopback wall of tessera-node (vulkan), %ux%u, median of %d still frames\n", scene.c_str(),
              width, height, frames);
  std::printf("%-24s | %9s %9s | %9s %9s | %6s | %8s\n", "view", "full ms", "tile ms", "guided ms", "tile ms", "ratio",
              "pixels differ");
  int status = 0;
  for (std::size_t i = 0; i < views.size(); ++i) {
    std::size_t differ = 0;
    for (std::size_t p = 0; p < all[i].image.colour.size(); ++p)
      differ += all[i].image.colour[p] != guided[i].image.colour[p];
    status |= differ != 0;
    std::printf("%-24s | %9.1f %9.1f | %9.1f %9.1f | %5.1fx | %8zu\n", names[i], all[i].frame * 1e3,
                all[i].slowestTile * 1e3, guided[i].frame * 1e3, guided[i].slowestTile * 1e3,
                all[i].frame / guided[i].frame, differ);
  }
  return status;
}
