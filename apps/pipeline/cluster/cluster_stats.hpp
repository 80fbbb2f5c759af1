#pragma once
// tessera-render --stats-json with --cluster: per frame and per node, who
// rendered which tiles and what they cost (tiles, pixels, samples, rays,
// milliseconds), with each frame's balance (the slowest node's render time
// over the mean); the same figures summed over the sequence.
#include <cstdint>
#include <string>
#include <vector>

#include "render_job.hpp"
#include "tsr/cluster/cluster_window.hpp"

namespace tsr::app {

struct ClusterFrameRecord {
  int frame = 0;       // in the sequence
  double seconds = 0;  // the client's: publishing the frame and rendering it on the nodes
  std::vector<cluster::TileWork> tiles;
  cluster::FrameWorkload workload;
};

// What a cluster sequence's frames cost, recorded as they render.
class ClusterStatsLog {
 public:
  void record(int frame, double seconds, const cluster::ClusterFrame& rendered, const cluster::ClusterWindow& window);
  const std::vector<ClusterFrameRecord>& frames() const { return frames_; }

  // Writes the log to options.statsJson (replacing it whole); throws
  // std::runtime_error when it cannot be written.
  void write(const RenderJob& options) const;

 private:
  std::vector<ClusterFrameRecord> frames_;
  std::vector<cluster::NodeStatus> nodes_;  // as of the last frame: addresses and names
  std::string mode_, backend_;              // the window's config
};

}  // namespace tsr::app
