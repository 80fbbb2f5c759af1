#pragma once
// How one cluster mode turns a view into work and the results into a frame
// (Schwenk 5.3.4): a wall renders one screen per node and swaps at a
// barrier, cooperative rendering balances tiles over the nodes, stereo
// renders one eye per node. The ClusterWindow owns the nodes and the
// message loop; the strategy decides the work, who takes over the items of
// a lost node, and how the targets become the application's frame.
#include <map>
#include <memory>
#include <vector>

#include "client/frame_round.hpp"
#include "tsr/cluster/cluster_config.hpp"

namespace tsr::cluster {

struct ClusterFrame;

struct Eyes {
  float separation = 0.065f;
  float zeroParallax = 5.0f;
};

class FrameStrategy {
 public:
  virtual ~FrameStrategy() = default;

  // The frame's work over the live nodes (config order indices), and the
  // buffers its pixels go into (allocated here).
  virtual std::vector<WorkItem> plan(const med::View& view, const Eyes& eyes, const std::vector<std::size_t>& live,
                                     std::vector<med::FrameBuffer>& targets) = 0;
  // Viewports each node holds (ids 0..n-1).
  virtual std::uint32_t viewportsPerNode() const { return 1; }
  // A frame can render with no node online (a wall shows offline fill).
  virtual bool needsNodes() const { return true; }
  // `lost` went away holding `pending` items of `round`: which live node
  // takes each one. Items not in the answer are given up (offline fill).
  virtual std::map<std::size_t, std::vector<std::size_t>> takeOver(const FrameRound& round, std::size_t lost,
                                                                   const std::vector<std::size_t>& pending,
                                                                   const std::vector<std::size_t>& live) = 0;
  virtual void tileDone(const WorkItem& /*item*/, double /*seconds*/) {}
  // Every item is in or given up. True: the nodes that delivered present
  // the frame now (the swap barrier).
  virtual bool frameDone() { return false; }
  // The application's frame from the assembled (and resolved) targets.
  virtual void compose(std::vector<med::FrameBuffer>& targets, ClusterFrame& out) const;
  virtual double imbalance() const { return 1.0; }
};

// Targets 0 and 1 (left, right eye) into the frame's eyes and their composition.
void composeEyes(std::vector<med::FrameBuffer>& targets, StereoCompose compose, ClusterFrame& out);

std::unique_ptr<FrameStrategy> makeCooperativeStrategy(const CooperativeConfig& config);
std::unique_ptr<FrameStrategy> makeWallStrategy(const WallConfig& wall, StereoCompose compose);
std::unique_ptr<FrameStrategy> makeStereoStrategy(StereoCompose compose);
std::unique_ptr<FrameStrategy> makeFrameStrategy(const ClusterConfig& config);

}  // namespace tsr::cluster
