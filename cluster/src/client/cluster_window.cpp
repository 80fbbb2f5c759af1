#include "tsr/cluster/cluster_window.hpp"

#include <algorithm>
#include <array>

#include "client/cluster_window_impl.hpp"
#include "tsr/sg/wire/wire_codec.hpp"

namespace tsr::cluster {

const char* name(NodePhase phase) {
  // In NodePhase's order. The assert catches a table out of step with the
  // enumerators up to the last one named there; a phase appended after it
  // needs its name here and the assert moved to it.
  static constexpr std::array kNames{"idle", "connect", "snapshot", "render", "barrier"};
  static_assert(kNames.size() == std::size_t(NodePhase::Barrier) + 1);
  return std::size_t(phase) < kNames.size() ? kNames[std::size_t(phase)] : "?";
}

ClusterWindow::ClusterWindow(ClusterConfig config, ClientOptions options)
    : impl_(std::make_unique<Impl>(std::move(config), std::move(options))) {
  impl_->config.validate();
  const ClusterConfig& c = impl_->config;
  if (impl_->wantsWorkload() && (c.mode == ClusterMode::Stereo || (c.mode == ClusterMode::Tiled && c.wall.stereo())))
    throw ClusterError(std::string("the ") + std::string(kWorkloadOutput) +
                       " image needs a cooperative or mono tiled cluster: a stereo one renders two eyes, no one frame");
  for (const auto& n : impl_->config.nodes) impl_->add(n);
}

ClusterWindow::~ClusterWindow() = default;

std::size_t ClusterWindow::connect(std::chrono::milliseconds timeout) {
  Impl& s = *impl_;
  for (std::size_t i = 0; i < s.nodes.size(); ++i)
    if (s.nodes[i].state == NodeState::Offline) s.startConnecting(i);
  s.pump(Clock::now() + timeout, [&] {
    return std::none_of(s.nodes.begin(), s.nodes.end(),
                        [](const ClusterNode& n) { return n.state == NodeState::Connecting; });
  });
  return onlineNodes();
}

std::size_t ClusterWindow::addNode(NodeConfig node) {
  std::size_t i = impl_->add(std::move(node));
  impl_->config.nodes.push_back(impl_->nodes[i].config);
  impl_->startConnecting(i);
  return i;
}

void ClusterWindow::setContent(sg::ContainerId root, sg::ContainerId background) {
  Impl& s = *impl_;
  s.root = root;
  s.background = background;
  for (auto& n : s.nodes)
    if (n.state == NodeState::Synced) n.link->send(s.viewportsFor(n));
}

void ClusterWindow::publish(const sg::Scene& scene, const sg::ChangeListPtr& delta) {
  Impl& s = *impl_;
  s.drain();
  s.retryOffline();
  Frame changes;
  std::vector<Frame> snapshot;
  for (auto& n : s.nodes) {
    bool follows = n.state == NodeState::Synced && delta && n.sentVersion == delta->baseVersion();
    if (n.state == NodeState::Synced && !delta && n.sentVersion == scene.version()) continue;
    if (n.applied >= n.sentVersion) n.listSentAt = Clock::now();  // it was caught up: a new wait begins
    if (follows) {
      if (!changes) changes = changeListFrame(Changes::kType, *delta);
      n.link->send(changes);
    } else if (n.state == NodeState::Synced || n.state == NodeState::Joined) {
      // A new node, or one that missed a list: it starts over from the whole scene.
      if (snapshot.empty())
        for (const auto& part :
             sg::splitSnapshot(scene.snapshot(), s.snapshotPartBytes(Snapshot::kSpec), s.messageBytes(Snapshot::kSpec)))
          snapshot.push_back(changeListFrame(Snapshot::kType, *part));
      for (const Frame& part : snapshot) n.link->send(part);
      if (!n.viewportsSent) n.link->send(s.viewportsFor(n));
      n.viewportsSent = true;
      s.setState(n, NodeState::Synced);
    } else {
      continue;
    }
    n.sentVersion = scene.version();
  }
}

void ClusterWindow::prepare(const sg::Scene& ahead, const sg::ChangeListPtr& delta, std::int64_t frame) {
  Impl& s = *impl_;
  s.drain();
  Frame changes;
  std::vector<Frame> snapshot;
  for (auto& n : s.nodes) {
    if (n.state != NodeState::Synced && n.state != NodeState::Joined) {
      n.aheadVersion.reset();  // when it is back, it starts over from the whole scene ahead
      continue;
    }
    if (!n.viewportsSent) {
      // Before the first publish (the animation's first frames are prepared
      // before any is shown): the viewports that prepare them.
      n.link->send(s.viewportsFor(n));
      n.viewportsSent = true;
    }
    if (delta && n.aheadVersion && *n.aheadVersion == delta->baseVersion()) {
      if (!changes) changes = makeFrame(Prepare{frame, sg::encode(*delta)});
      n.link->send(changes);
    } else {
      if (snapshot.empty())
        for (const auto& part :
             sg::splitSnapshot(ahead.snapshot(), s.snapshotPartBytes(Prepare::kSpec), s.messageBytes(Prepare::kSpec)))
          snapshot.push_back(makeFrame(Prepare{frame, sg::encode(*part)}));
      for (const Frame& part : snapshot) n.link->send(part);
    }
    n.aheadVersion = ahead.version();
  }
}

bool ClusterWindow::waitApplied(std::uint64_t version, std::chrono::milliseconds timeout) {
  Impl& s = *impl_;
  return s.pump(Clock::now() + timeout, [&] {
    return std::all_of(s.nodes.begin(), s.nodes.end(),
                       [&](const ClusterNode& n) { return n.state != NodeState::Synced || n.applied >= version; });
  });
}

std::vector<ReplicaHash> ClusterWindow::replicaHashes(std::chrono::milliseconds timeout) {
  Impl& s = *impl_;
  ++s.hashToken;
  std::vector<std::size_t> asked = s.synced();
  for (std::size_t i : asked) {
    s.nodes[i].hash.reset();
    s.nodes[i].link->send(makeFrame(HashQuery{s.hashToken}));
  }
  s.pump(Clock::now() + timeout, [&] {
    return std::all_of(asked.begin(), asked.end(),
                       [&](std::size_t i) { return s.nodes[i].state != NodeState::Synced || s.nodes[i].hash; });
  });
  std::vector<ReplicaHash> out;
  for (std::size_t i : asked)
    if (s.nodes[i].state == NodeState::Synced && s.nodes[i].hash)
      out.push_back({i, s.nodes[i].hash->version, s.nodes[i].hash->hash});
  return out;
}

void ClusterWindow::setProgress(std::function<void(double)> progress) { impl_->progress = std::move(progress); }

// One frame in steps: plan and send the work, wait for it (moving the work
// of nodes lost on the way), release the barrier, then record and compose.
ClusterFrame ClusterWindow::render(const med::View& view, std::int64_t sequenceFrame) {
  Impl& s = *impl_;
  view.validate();
  s.drain();
  std::vector<std::size_t> live = s.synced();
  if (live.empty() && s.strategy->needsNodes()) throw ClusterError("no cluster node is online");

  ClusterFrame result;
  result.frame = ++s.frame;
  std::vector<med::FrameBuffer> targets;
  std::vector<WorkItem> items = s.strategy->plan(view, s.eyes, live, targets);
  // Pixels left on the nodes are resolved there: the client never sees them.
  result.pixelsKept = s.keepPixels && s.config.mode == ClusterMode::Tiled;
  if (!result.pixelsKept) {
    s.resolver.make(s.nodes, s.options, s.root, s.background);
    s.resolver.askOutputs(s.options, items, targets);
  }
  FrameRound round(result.frame, std::move(items), targets,
                   result.pixelsKept ? Compression::Kept : s.config.compression, sequenceFrame);
  s.reassigned = 0;

  s.sendRequests(round);
  s.awaitFrame(round, result.lateNodes);
  s.finishFrame(round, result.frame);
  s.recordWork(round, live, result);
  if (!result.pixelsKept) s.resolver.resolve(s.options, targets);
  s.strategy->compose(targets, result);
  if (s.wantsWorkload() && !result.image.colour.empty())
    result.image.outputs[std::string(kWorkloadOutput)] =
        drawWorkload(result.tiles, result.image.width, result.image.height);
  return result;
}

void ClusterWindow::Impl::sendRequests(FrameRound& round) {
  for (std::size_t i = 0; i < round.items().size(); ++i)
    if (nodes[round.items()[i].node].state != NodeState::Synced) round.giveUp(i, config.wall.offlineColour);
  for (auto& [node, its] : round.pendingByNode()) {
    nodes[node].link->send(round.request(its));
    nodes[node].requestAt = Clock::now();
    nodes[node].longestWait = {};
    round.sent(node);
  }
}

void ClusterWindow::Impl::awaitFrame(FrameRound& round, std::vector<std::string>& lateNodes) {
  auto deadline = Clock::now() + config.timeouts.frame;
  while (!round.finished()) {
    if (!round.error().empty()) throw ClusterError(round.error());
    if (strategy->needsNodes() && synced().empty()) throw ClusterError("every cluster node was lost during the frame");
    // Wakes now and then to say who is late, short of the deadline.
    auto wake = std::min(deadline, Clock::now() + config.timeouts.late / 4);
    bool done = pump(
        wake, [&] { return round.finished() || !round.error().empty(); }, &round);
    reportLate(round, lateNodes);
    if (!done && Clock::now() >= deadline) {
      // Nodes that missed the frame deadline are dropped; their work moves or shows as offline.
      for (std::size_t node : round.awaited()) lose(node, "missed the frame deadline", &round);
      deadline = Clock::now() + config.timeouts.frame;
    }
  }
}

void ClusterWindow::Impl::finishFrame(const FrameRound& round, std::uint64_t frameNumber) {
  // What this frame cost each node that delivered it is what the next may cost.
  for (std::size_t n : synced())
    if (round.delivered(n)) {
      nodes[n].expectedWait = nodes[n].longestWait;
      nodes[n].finishedAFrame = true;
    }
  if (strategy->frameDone()) {
    // The barrier: every tile is in (or given up), so the wall swaps at once.
    for (std::size_t n : synced())
      if (round.delivered(n)) nodes[n].link->send(makeFrame(Swap{frameNumber}));
  }
}

void ClusterWindow::Impl::recordWork(const FrameRound& round, const std::vector<std::size_t>& live,
                                     ClusterFrame& result) {
  result.busySeconds.assign(nodes.size(), 0.0);
  for (const auto& [node, busy] : round.busySeconds()) result.busySeconds[node] = busy;
  result.tileSeconds.assign(nodes.size(), 0.0);
  for (const auto& [node, t] : round.tileSeconds()) result.tileSeconds[node] = t;
  for (const auto& it : round.items()) result.offlineTiles += it.offline ? 1 : 0;
  for (const auto& it : round.items())
    if (it.done || it.offline)
      result.tiles.push_back(
          {it.rect, it.offline ? TileWork::kNoNode : it.node, it.seconds, it.samples, it.rays, it.syncSeconds});
  result.participants = live;
  lastWorkload = summarizeWorkload(result.tiles, result.busySeconds, live, nodes.size());
  result.reassignedItems = reassigned;
  result.assembleSeconds = round.assembleSeconds();
  result.barrierSeconds = round.barrierSeconds();
}

void ClusterWindow::keepPixelsOnNodes(bool keep) { impl_->keepPixels = keep; }

void ClusterWindow::setEyes(float separation, float zeroParallax) {
  // The config's values, where it gives them, win over the application's.
  impl_->eyes.separation = impl_->config.stereo.eyeSeparation.value_or(separation);
  impl_->eyes.zeroParallax = impl_->config.stereo.zeroParallax.value_or(zeroParallax);
}

std::vector<NodeStatus> ClusterWindow::status() const {
  std::vector<NodeStatus> out;
  for (std::size_t i = 0; i < impl_->nodes.size(); ++i) {
    const ClusterNode& n = impl_->nodes[i];
    auto [phase, since] = impl_->phaseOf(i, nullptr);
    out.push_back({n.config.address, n.name, n.state, n.applied, n.link->bytesSent(), n.link->bytesReceived(),
                   n.lastError, phase, since, n.lastReport});
  }
  return out;
}

std::size_t ClusterWindow::onlineNodes() const {
  return static_cast<std::size_t>(std::count_if(impl_->nodes.begin(), impl_->nodes.end(), [](const ClusterNode& n) {
    return n.state == NodeState::Joined || n.state == NodeState::Synced;
  }));
}

const ClusterConfig& ClusterWindow::config() const { return impl_->config; }

double ClusterWindow::estimatedImbalance() const { return impl_->strategy->imbalance(); }

const FrameWorkload& ClusterWindow::lastWorkload() const { return impl_->lastWorkload; }

}  // namespace tsr::cluster
