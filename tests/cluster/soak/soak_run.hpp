#pragma once
// A long cluster run on four loopback nodes (issue 17): builtin:animated in
// one cluster mode, a replica hash check every few frames, node memory and
// descriptors at start and end, and faults injected along the way. Used by
// the short CTest version (soak_test.cpp) and the long script
// (scripts/soak.sh through tsr_soak).
#include <functional>
#include <string>
#include <vector>

#include "tsr/cluster/cluster_config.hpp"

namespace tsr::cluster::test {

struct SoakOptions {
  ClusterMode mode = ClusterMode::Cooperative;
  int frames = 300;
  int hashEvery = 25;
  std::uint32_t size = 32;  // square image
  bool faults = true;
  std::string renderBinary;  // tessera-render for the killed-client fault; empty: that fault is left out
  std::function<void(const std::string&)> log;  // progress lines; may be empty
};

struct NodeUsage {
  long rssKiB = 0;
  int fds = 0;
};

struct FaultOutcome {
  std::string name;
  int framesAffected = 0;           // frames rendered while the fault lasted or recovery ran
  std::size_t offlineTiles = 0;     // wall tiles shown as offline fill: pixels lost
  std::size_t reassignedItems = 0;  // work redone by other nodes: nothing lost, time spent
  int failedFrames = 0;             // render() threw: the frame was lost
  double recoverySeconds = -1;      // from the fault's end until every node was synced again; -1: never
  double frameSlowdown = 0;         // median frame time during the fault over the baseline's
  std::string detail;
};

struct SoakReport {
  int frames = 0;
  int hashChecks = 0;
  int nodesChecked = 0;  // node replicas compared, over all checks
  int divergences = 0;
  int failedFrames = 0;
  double baselineFrameSeconds = 0;    // median before the first fault
  std::vector<NodeUsage> start, end;  // per node, after the first frame and at the end
  long peakRssKiB = 0;                // largest node RSS seen at any sample
  std::vector<FaultOutcome> faults;
};

// Runs the soak; throws std::runtime_error when the cluster cannot start.
SoakReport runSoak(const SoakOptions& options);

std::string modeName(ClusterMode mode);
std::string describe(const SoakReport& report);

}  // namespace tsr::cluster::test
