// Who is late: where each node stands in the running frame, since when, and
// how long it may stay there judged by what its frames cost.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>

#include <spdlog/spdlog.h>

#include "client/cluster_window_impl.hpp"

namespace tsr::cluster {

namespace {
// A node's first frame after joining builds its scene and warms up: it is
// late only past this many times timeouts.late. Later frames, past twice
// the longest wait for one tile in its previous frame (or timeouts.late).
constexpr int kFirstFrameGrace = 10;
constexpr int kExpectedWaitFactor = 2;

// A steady-clock instant as wall-clock time of day, for people reading logs.
std::string timeOfDay(Clock::time_point t) {
  auto wall = std::chrono::system_clock::now() -
              std::chrono::duration_cast<std::chrono::system_clock::duration>(Clock::now() - t);
  std::time_t tt = std::chrono::system_clock::to_time_t(wall);
  std::tm tm{};
  localtime_r(&tt, &tm);
  auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(wall.time_since_epoch()).count() % 1000;
  char text[32];
  std::snprintf(text, sizeof text, "%02d:%02d:%02d.%03d", tm.tm_hour, tm.tm_min, tm.tm_sec, static_cast<int>(ms));
  return text;
}
}  // namespace

std::pair<NodePhase, Clock::time_point> ClusterWindow::Impl::phaseOf(std::size_t i, const FrameRound* round) const {
  const ClusterNode& n = nodes[i];
  if (n.state == NodeState::Offline || n.state == NodeState::Connecting) return {NodePhase::Connect, n.stateSince};
  if (n.state == NodeState::Joined) return {NodePhase::Snapshot, n.stateSince};
  if (n.applied < n.sentVersion) return {NodePhase::Snapshot, n.listSentAt};
  if (round) {
    auto awaited = round->awaited();
    if (std::find(awaited.begin(), awaited.end(), i) != awaited.end()) {
      // Each tile that arrives shows the node at work: it is waited for
      // since its request or its latest tile.
      if (!round->pendingOf(i).empty()) return {NodePhase::Render, std::max(n.requestAt, n.lastTileAt)};
      return {NodePhase::Barrier, std::max(n.requestAt, n.lastTileAt)};
    }
  }
  return {NodePhase::Idle, n.stateSince};
}

Clock::duration ClusterWindow::Impl::lateAfter(const ClusterNode& n) const {
  if (!n.finishedAFrame) return kFirstFrameGrace * config.timeouts.late;
  return std::max<Clock::duration>(config.timeouts.late, kExpectedWaitFactor * n.expectedWait);
}

void ClusterWindow::Impl::reportLate(const FrameRound& round, std::vector<std::string>& late) {
  auto now = Clock::now();
  for (std::size_t i : round.awaited()) {
    auto [phase, since] = phaseOf(i, &round);
    ClusterNode& n = nodes[i];
    if (phase == NodePhase::Idle || now - since < lateAfter(n)) continue;
    if (n.reportedLate == std::pair{round.frame(), phase}) continue;
    n.reportedLate = {round.frame(), phase};
    std::string line = n.config.address.text() + " (" + (n.name.empty() ? "?" : n.name) + "): " + name(phase) +
                       " since " + timeOfDay(since) + " (" +
                       std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(now - since).count()) +
                       " ms)";
    spdlog::warn("frame {}: node {} is late", round.frame(), line);
    late.push_back(std::move(line));
  }
}

}  // namespace tsr::cluster
