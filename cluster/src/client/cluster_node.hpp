#pragma once
// What the client knows of one node: its config, its link, where its
// session stands and what its frames cost (for judging it late).

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "client/node_link.hpp"
#include "tsr/cluster/cluster_config.hpp"
#include "tsr/cluster/cluster_window.hpp"
#include "tsr/cluster/messages.hpp"

namespace tsr::cluster {

using Clock = std::chrono::steady_clock;

struct ClusterNode {
  NodeConfig config;
  std::shared_ptr<NodeLink> link;
  NodeState state = NodeState::Offline;
  std::uint64_t generation = 0;
  Clock::time_point retryAt{};
  std::string name;
  std::uint64_t applied = 0;
  std::uint64_t sentVersion = 0;
  // The scene ahead (prepare()): the version sent, none before the first.
  std::optional<std::uint64_t> aheadVersion;
  bool viewportsSent = false;  // SetViewports sent since it joined
  std::string lastError;
  std::optional<ErrorReport> lastReport;  // the node's last ErrorReport since it joined
  std::optional<HashReply> hash;          // the answer to the latest HashQuery
  // When the phases the client may wait in began (see phaseOf).
  Clock::time_point stateSince = Clock::now(), listSentAt{}, requestAt{}, lastTileAt{};
  std::pair<std::uint64_t, NodePhase> reportedLate{0, NodePhase::Idle};
  // What a frame costs this node, for judging it late: the longest wait
  // for its next tile (after the request or the tile before) in this frame
  // and in the last one it finished since it joined (none yet: its first).
  Clock::duration longestWait{}, expectedWait{};
  bool finishedAFrame = false;
};

}  // namespace tsr::cluster
