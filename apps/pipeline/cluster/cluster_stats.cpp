#include "cluster/cluster_stats.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "tsr/med/file_replacement.hpp"

namespace tsr::app {

namespace {
const char* modeName(cluster::ClusterMode mode) {
  switch (mode) {
    case cluster::ClusterMode::Cooperative:
      return "cooperative";
    case cluster::ClusterMode::Tiled:
      return "tiled";
    case cluster::ClusterMode::Stereo:
      return "stereo";
  }
  return "?";
}

nlohmann::json nodeJson(std::size_t i, const cluster::NodeWork& n) {
  return {{"node", i},
          {"tiles", n.tiles},
          {"pixels", n.pixels},
          {"samples", n.samples},
          {"rays", n.rays},
          {"milliseconds", n.seconds * 1e3},
          {"sync_milliseconds", n.syncSeconds * 1e3},
          {"busy_milliseconds", n.busySeconds * 1e3}};
}
}  // namespace

void ClusterStatsLog::record(int frame, double seconds, const cluster::ClusterFrame& rendered,
                             const cluster::ClusterWindow& window) {
  nodes_ = window.status();
  mode_ = modeName(window.config().mode);
  backend_ = window.config().nodes.empty() ? std::string() : window.config().nodes.front().backend;
  frames_.push_back({frame, seconds, rendered.tiles, window.lastWorkload()});
}

void ClusterStatsLog::write(const RenderJob& options) const {
  const std::size_t nodeCount = nodes_.size();
  std::vector<cluster::NodeWork> total(nodeCount);
  double seconds = 0, balanceSum = 0, balanceMax = 0;
  std::uint64_t rays = 0;
  std::uint32_t spp = 0;
  nlohmann::json perFrame = nlohmann::json::array();
  for (const auto& f : frames_) {
    seconds += f.seconds;
    balanceSum += f.workload.balance;
    balanceMax = std::max(balanceMax, f.workload.balance);
    nlohmann::json nodes = nlohmann::json::array(), tiles = nlohmann::json::array();
    for (std::size_t i = 0; i < f.workload.nodes.size() && i < nodeCount; ++i) {
      const cluster::NodeWork& n = f.workload.nodes[i];
      nodes.push_back(nodeJson(i, n));
      cluster::NodeWork& t = total[i];
      t.tiles += n.tiles;
      t.pixels += n.pixels;
      t.samples += n.samples;
      t.rays += n.rays;
      t.seconds += n.seconds;
      t.syncSeconds += n.syncSeconds;
      t.busySeconds += n.busySeconds;
      rays += n.rays;
    }
    for (const auto& t : f.tiles) {
      spp = std::max(spp, t.samples);
      tiles.push_back(
          {{"rect", {t.rect.x0, t.rect.y0, t.rect.x1, t.rect.y1}},
           {"node", t.node == cluster::TileWork::kNoNode ? nlohmann::json(nullptr) : nlohmann::json(t.node)},
           {"milliseconds", t.seconds * 1e3},
           {"sync_milliseconds", t.syncSeconds * 1e3},
           {"samples", t.samples},
           {"rays", t.rays}});
    }
    perFrame.push_back({{"frame", f.frame},
                        {"seconds", f.seconds},
                        {"balance", f.workload.balance},
                        {"nodes", std::move(nodes)},
                        {"tiles", std::move(tiles)}});
  }
  nlohmann::json nodes = nlohmann::json::array();
  for (std::size_t i = 0; i < nodeCount; ++i) {
    nlohmann::json n = nodeJson(i, total[i]);
    n["address"] = nodes_[i].address.text();
    n["name"] = nodes_[i].name;
    nodes.push_back(std::move(n));
  }
  const double frames = static_cast<double>(frames_.size());
  nlohmann::json j = {{"scene", options.scene},
                      {"backend", backend_.empty() ? options.backend : backend_},
                      {"mode", mode_},
                      {"frames", frames_.size()},
                      {"seconds", seconds},
                      {"spp", spp},
                      {"width", options.width},
                      {"height", options.height},
                      {"rays", rays},
                      {"rays_per_second", seconds > 0 ? double(rays) / seconds : 0.0},
                      {"balance_mean", frames > 0 ? balanceSum / frames : 1.0},
                      {"balance_max", frames > 0 ? balanceMax : 1.0},
                      {"nodes", std::move(nodes)},
                      {"per_frame", std::move(perFrame)}};
  med::replaceTextFile(options.statsJson, j.dump(2) + "\n");
}

}  // namespace tsr::app
