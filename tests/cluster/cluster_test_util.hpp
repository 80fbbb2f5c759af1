#pragma once
// Shared set-up of the cluster integration tests: configs for nodes
// started on free ports, and the animated built-in scene.
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "node_process.hpp"
#include "tsr/cluster/cluster_config.hpp"
#include "tsr/med/frame_buffer.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::cluster::test {

// A fresh folder under /tmp, removed with everything in it.
struct TempDir {
  std::filesystem::path path;
  TempDir() {
    char name[] = "/tmp/tsr-cluster-XXXXXX";
    path = mkdtemp(name);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
};

inline ClusterConfig configFor(ClusterMode mode, const std::vector<std::unique_ptr<NodeProcess>>& nodes,
                               const med::Parameters& parameters = {}) {
  ClusterConfig c;
  c.mode = mode;
  for (const auto& n : nodes) c.nodes.push_back({n->address(), "embree", parameters});
  c.timeouts.retry = std::chrono::milliseconds(100);
  c.timeouts.connect = std::chrono::milliseconds(3000);
  c.timeouts.frame = std::chrono::milliseconds(60000);
  return c;
}

struct AnimatedScene {
  sg::Scene scene;
  sg::ImportResult imported;
  AnimatedScene(const std::string& source = "builtin:animated") { imported = sg::importScene(scene, source); }
  // Poses the animation at frame `i` of a 24 fps clip, with its motion over
  // the frame when a shutter is open (as the programs do).
  void pose(int i, bool shutterOpen = false) {
    for (const auto& a : imported.animations)
      a.apply(scene, static_cast<float>(i) / 24.0f, shutterOpen ? 1.0f / 24.0f : 0.0f);
  }
};

inline bool bitwiseEqual(const med::FrameBuffer& a, const med::FrameBuffer& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.colour.data(), b.colour.data(), a.colour.size() * sizeof(glm::vec4)) == 0 &&
         std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * sizeof(float)) == 0;
}

}  // namespace tsr::cluster::test
