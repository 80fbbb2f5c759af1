#include "tsr/cluster/cluster_window.hpp"

#include <algorithm>
#include <ctime>
#include <optional>
#include <thread>

#include <spdlog/spdlog.h>

#include "client/frame_round.hpp"
#include "client/node_link.hpp"
#include "modes/frame_strategy.hpp"
#include "tsr/cluster/protocol_error.hpp"
#include "tsr/sg/wire_codec.hpp"

namespace tsr::cluster {

using Clock = std::chrono::steady_clock;

const char* name(NodePhase phase) {
  switch (phase) {
    case NodePhase::Idle:
      return "idle";
    case NodePhase::Connect:
      return "connect";
    case NodePhase::Snapshot:
      return "snapshot";
    case NodePhase::Render:
      return "render";
    case NodePhase::Barrier:
      return "barrier";
  }
  return "?";
}

namespace {
struct Node {
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

// A node's first frame after joining builds its scene and warms up: it is
// late only past this many times timeouts.late. Later frames, past twice
// the longest wait for one tile in its previous frame (or timeouts.late).
constexpr int kFirstFrameGrace = 10;
constexpr int kExpectedWaitFactor = 2;

// A node that cannot render the frame as asked (a back-end it lacks, a
// parameter its back-end refuses, an output it cannot fill) would fail the
// same way on every node the work moves to: the frame fails at once. A
// rejected scene, a broken message or a failed prepare only lose that node.
bool failsTheFrame(ErrorReport::Kind kind) {
  using Kind = ErrorReport::Kind;
  switch (kind) {
    case Kind::UnknownBackend:
    case Kind::InvalidParameter:
    case Kind::RenderFailed:
      return true;
    case Kind::ProtocolViolation:
    case Kind::SceneRejected:
    case Kind::PrepareFailed:
      return false;
  }
  return false;
}

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

struct ClusterWindow::Impl {
  ClusterConfig config;
  ClientOptions options;
  asio::io_context io;
  asio::executor_work_guard<asio::io_context::executor_type> work{io.get_executor()};
  std::thread thread;
  Inbox inbox;
  std::vector<Node> nodes;

  std::unique_ptr<FrameStrategy> strategy;
  std::function<void(double)> progress;
  std::size_t reassigned = 0;
  std::uint64_t hashToken = 0;
  std::uint64_t frame = 0;
  bool keepPixels = false;
  Eyes eyes;
  sg::ContainerId root = sg::kNoContainer, background = sg::kNoContainer;
  // The local viewport that resolves assembled frames, and what it needs.
  med::ContextPool resolverContexts;
  std::unique_ptr<med::Viewport> resolver;
  std::vector<std::string> resolveInputs;
  std::vector<std::string> resolveOutputs;
  FrameWorkload lastWorkload;

  Impl(ClusterConfig c, ClientOptions o) : config(std::move(c)), options(std::move(o)) {
    strategy = makeFrameStrategy(config);
    eyes.separation = config.stereo.eyeSeparation.value_or(eyes.separation);
    eyes.zeroParallax = config.stereo.zeroParallax.value_or(eyes.zeroParallax);
    thread = std::thread([this] { io.run(); });
  }
  ~Impl() {
    // What is queued (the last frame's Swap among it) goes out before the
    // Bye; a node that does not take it within a moment is closed anyway.
    for (auto& n : nodes)
      if (n.link) n.link->finish(makeFrame(Bye{}));
    auto until = Clock::now() + std::chrono::milliseconds(500);
    while (Clock::now() < until &&
           std::any_of(nodes.begin(), nodes.end(), [](const Node& n) { return n.link && n.link->running(); }))
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    for (auto& n : nodes)
      if (n.link) n.link->close();
    work.reset();
    io.stop();
    thread.join();
  }

  std::size_t add(NodeConfig c) {
    Node n;
    n.config = std::move(c);
    nodes.push_back(std::move(n));
    std::size_t i = nodes.size() - 1;
    nodes[i].link = std::make_shared<NodeLink>(io, i, nodes[i].config.address, options.token, config.timeouts, inbox);
    return i;
  }

  void setState(Node& n, NodeState state) {
    if (n.state != state) n.stateSince = Clock::now();
    if (state == NodeState::Joined || state == NodeState::Offline) {  // a new session
      n.viewportsSent = false;
      n.finishedAFrame = false;
    }
    n.state = state;
  }

  // Where node i stands, and since when; `round` is the running frame (or null).
  std::pair<NodePhase, Clock::time_point> phaseOf(std::size_t i, const FrameRound* round) const {
    const Node& n = nodes[i];
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

  // How long node i may stay in one phase of this frame before it is late:
  // judged by what its frames cost, not by one fixed time.
  Clock::duration lateAfter(const Node& n) const {
    if (!n.finishedAFrame) return kFirstFrameGrace * config.timeouts.late;
    return std::max<Clock::duration>(config.timeouts.late, kExpectedWaitFactor * n.expectedWait);
  }

  // Says once per frame and phase which awaited node is late, in which phase and since when.
  void reportLate(const FrameRound& round, std::vector<std::string>& late) {
    auto now = Clock::now();
    for (std::size_t i : round.awaited()) {
      auto [phase, since] = phaseOf(i, &round);
      Node& n = nodes[i];
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

  void startConnecting(std::size_t i) {
    Node& n = nodes[i];
    setState(n, NodeState::Connecting);
    n.link->start(++n.generation);
  }

  void retryOffline() {
    auto now = Clock::now();
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (nodes[i].state == NodeState::Offline && now >= nodes[i].retryAt) startConnecting(i);
  }

  // Sets a node offline and lets the running frame (if any) give its work away.
  void lose(std::size_t i, const std::string& why, FrameRound* round) {
    Node& n = nodes[i];
    if (n.state == NodeState::Offline) return;
    bool wasIn = n.state == NodeState::Synced;
    spdlog::warn("node {} ({}) lost: {}", n.config.address.text(), n.name, why);
    n.link->close();
    ++n.generation;  // events of the old connection no longer count
    setState(n, NodeState::Offline);
    n.lastError = why;
    n.retryAt = Clock::now() + config.timeouts.retry;
    if (!round) return;
    round->forget(i);
    if (wasIn) takeOver(*round, i);
  }

  std::vector<std::size_t> synced() const {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (nodes[i].state == NodeState::Synced) out.push_back(i);
    return out;
  }

  // The work of a lost node goes where the strategy says, within this
  // frame; what it places nowhere shows the offline fill.
  void takeOver(FrameRound& round, std::size_t lost) {
    std::vector<std::size_t> pending = round.pendingOf(lost);
    std::vector<std::size_t> live = synced();
    if (pending.empty() || (live.empty() && strategy->needsNodes())) return;  // render() notices and throws
    auto handed = strategy->takeOver(round, lost, pending, live);
    for (auto& [to, items] : handed) {
      for (std::size_t item : items) round.reassign(item, to);
      nodes[to].link->send(round.request(items));
      nodes[to].requestAt = Clock::now();
      round.sent(to);
      reassigned += items.size();
    }
    for (std::size_t item : round.pendingOf(lost)) round.giveUp(item, config.wall.offlineColour);
  }

  void handle(LinkEvent& e, FrameRound* round) {
    Node& n = nodes.at(e.node);
    if (e.generation != n.generation) return;
    switch (e.kind) {
      case LinkEvent::Kind::Connected:
        setState(n, NodeState::Joined);
        n.name = e.welcome.nodeName;
        n.applied = 0;
        n.lastReport.reset();
        // Kept even without the back-end: it still mirrors the scene; its renders fail and drop it then.
        if (std::find(e.welcome.backends.begin(), e.welcome.backends.end(), n.config.backend) ==
            e.welcome.backends.end())
          spdlog::warn("node {} has no back-end '{}'", n.config.address.text(), n.config.backend);
        spdlog::info("node {} ({}) joined", n.config.address.text(), n.name);
        return;
      case LinkEvent::Kind::Failed:
        if (n.lastError != e.reason) spdlog::warn("node {}: cannot connect: {}", n.config.address.text(), e.reason);
        setState(n, NodeState::Offline);
        n.lastError = e.reason;
        n.retryAt = Clock::now() + config.timeouts.retry;
        return;
      case LinkEvent::Kind::Closed:
        return lose(e.node, e.reason, round);
      case LinkEvent::Kind::Received:
        try {
          receive(e.node, e.message, round);
        } catch (const ProtocolError& err) {
          lose(e.node, std::string("protocol violation: ") + err.what(), round);
        }
        return;
    }
  }

  // One handler per message a node sends.
  // `round` is the frame being rendered, null between frames.
  void receive(std::size_t i, const Message& m, FrameRound* round) {
    switch (m.type) {
      case Applied::kType:
        nodes[i].applied = parse<Applied>(m).version;
        return;
      case RenderTile::kType: {
        RenderTile tile = parse<RenderTile>(m);
        if (!round) return;
        if (const WorkItem* done = round->onTile(i, tile)) {
          strategy->tileDone(*done, tile.seconds);
          Node& n = nodes[i];
          const auto now = Clock::now();
          n.longestWait = std::max(n.longestWait, now - std::max(n.requestAt, n.lastTileAt));
          n.lastTileAt = now;
          if (progress) {
            const auto& items = round->items();
            const auto done = std::count_if(items.begin(), items.end(), [](const WorkItem& w) { return w.done; });
            progress(double(done) / double(std::max<std::size_t>(1, items.size())));
          }
        }
        return;
      }
      case FrameDone::kType:
        if (round) round->onDone(i, parse<FrameDone>(m));
        return;
      case HashReply::kType: {
        HashReply r = parse<HashReply>(m);
        if (r.token == hashToken) nodes[i].hash = r;
        return;
      }
      case HeartbeatAck::kType:
        parse<HeartbeatAck>(m);
        return;
      case ErrorReport::kType: {
        Node& n = nodes[i];
        n.lastReport = parse<ErrorReport>(m);
        n.lastError = n.lastReport->reason;
        spdlog::warn("node {}: {} ({})", n.config.address.text(), n.lastError, name(n.lastReport->kind));
        if (round && failsTheFrame(n.lastReport->kind))
          round->fail("node " + n.config.address.text() + ": " + n.lastError);
        return;
      }
      default:
        throw ProtocolError(ProtocolError::Kind::Unexpected, std::string(name(m.type)) + " after the handshake");
    }
  }

  // Handles events until `done` holds or the deadline passes; `round` is
  // the frame they may belong to.
  template <class Done>
  bool pump(Clock::time_point deadline, Done done, FrameRound* round = nullptr) {
    while (!done()) {
      auto e = inbox.pop(deadline);
      if (!e) return done();
      handle(*e, round);
    }
    return true;
  }
  void drain() {
    pump(Clock::now(), [] { return false; });
  }

  // A resolver exists when every node runs the same back-end with the same
  // parameters (their frames are then one image) and that back-end has
  // whole-frame steps; made once, on the first frame.
  void makeResolver() {
    if (resolver || !options.registry || nodes.empty()) return;
    const NodeConfig& first = nodes.front().config;
    for (const auto& n : nodes)
      if (n.config.backend != first.backend || !(n.config.parameters == first.parameters)) return;
    if (!options.registry->has(first.backend)) return;
    resolver = options.registry->create({first.backend, root, background, first.parameters, true}, resolverContexts);
    resolveInputs = resolver->resolveInputs();
    resolveOutputs = resolver->resolveOutputs();
    if (resolveInputs.empty()) resolver.reset();
  }

  // What each work item asks the nodes for.
  // Nodes fill what the application reads and the resolver needs; what the
  // resolver makes itself is left out of their work.
  void askOutputs(std::vector<WorkItem>& items, std::vector<med::FrameBuffer>& targets) const {
    auto has = [](const std::vector<std::string>& v, const std::string& name) {
      return std::find(v.begin(), v.end(), name) != v.end();
    };
    std::vector<std::string> outputs;
    for (const auto& name : options.outputs)
      if ((!resolver || !has(resolveOutputs, name)) && name != kWorkloadOutput) outputs.push_back(name);
    for (const auto& name : resolver ? resolveInputs : std::vector<std::string>{})
      if (!has(outputs, name)) outputs.push_back(name);
    for (auto& it : items) {
      it.outputs = outputs;
      it.resolve = resolver == nullptr;
    }
    // Targets hold what nodes send and what the application reads (the
    // resolver fills the latter's remainder), each allocated once.
    std::vector<std::string> held = outputs;
    for (const auto& name : options.outputs)
      if (!has(held, name) && name != kWorkloadOutput) held.push_back(name);
    for (auto& t : targets)
      for (const auto& name : held) t.outputs[name].assign(t.colour.size(), glm::vec4(0.0f));
  }

  bool wantsWorkload() const {
    return std::find(options.outputs.begin(), options.outputs.end(), kWorkloadOutput) != options.outputs.end();
  }

  Frame viewportsFor(const Node& n) const {
    SetViewports sv;
    // A wall node's window goes where the config's screen says; without a
    // window entry, at the screen's place in the virtual frame.
    std::size_t i = static_cast<std::size_t>(&n - nodes.data());
    if (config.mode == ClusterMode::Tiled && i < config.wall.screens.size()) {
      const ScreenConfig& screen = config.wall.screens[i];
      sv.window = screen.window.value_or(WindowPlacement{screen.x, screen.y, 0, 0, false});
    }
    for (std::uint32_t id = 0; id < strategy->viewportsPerNode(); ++id)
      sv.viewports.push_back({id, n.config.backend, root, background, n.config.parameters});
    return makeFrame(sv);
  }
};

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
    return std::none_of(s.nodes.begin(), s.nodes.end(), [](const Node& n) { return n.state == NodeState::Connecting; });
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
  Frame changes, snapshot;
  for (auto& n : s.nodes) {
    bool follows = n.state == NodeState::Synced && delta && n.sentVersion == delta->baseVersion();
    if (n.state == NodeState::Synced && !delta && n.sentVersion == scene.version()) continue;
    if (n.applied >= n.sentVersion) n.listSentAt = Clock::now();  // it was caught up: a new wait begins
    if (follows) {
      if (!changes) changes = frameFromPayload(Changes::kType, sg::encode(*delta));
      n.link->send(changes);
    } else if (n.state == NodeState::Synced || n.state == NodeState::Joined) {
      // A new node, or one that missed a list: it starts over from the whole scene.
      if (!snapshot) snapshot = frameFromPayload(Snapshot::kType, sg::encode(*scene.snapshot()));
      n.link->send(snapshot);
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
  Frame changes, snapshot;
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
      if (!snapshot) snapshot = makeFrame(Prepare{frame, sg::encode(*ahead.snapshot())});
      n.link->send(snapshot);
    }
    n.aheadVersion = ahead.version();
  }
}

bool ClusterWindow::waitApplied(std::uint64_t version, std::chrono::milliseconds timeout) {
  Impl& s = *impl_;
  return s.pump(Clock::now() + timeout, [&] {
    return std::all_of(s.nodes.begin(), s.nodes.end(),
                       [&](const Node& n) { return n.state != NodeState::Synced || n.applied >= version; });
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
    s.makeResolver();
    s.askOutputs(items, targets);
  }
  FrameRound round(result.frame, std::move(items), targets,
                   result.pixelsKept ? Compression::Kept : s.config.compression, sequenceFrame);
  s.reassigned = 0;

  for (std::size_t i = 0; i < round.items().size(); ++i)
    if (s.nodes[round.items()[i].node].state != NodeState::Synced) round.giveUp(i, s.config.wall.offlineColour);
  for (auto& [node, its] : round.pendingByNode()) {
    s.nodes[node].link->send(round.request(its));
    s.nodes[node].requestAt = Clock::now();
    s.nodes[node].longestWait = {};
    round.sent(node);
  }

  auto deadline = Clock::now() + s.config.timeouts.frame;
  while (!round.finished()) {
    if (!round.error().empty()) throw ClusterError(round.error());
    if (s.strategy->needsNodes() && s.synced().empty())
      throw ClusterError("every cluster node was lost during the frame");
    // Wakes now and then to say who is late, short of the deadline.
    auto wake = std::min(deadline, Clock::now() + s.config.timeouts.late / 4);
    bool done = s.pump(
        wake, [&] { return round.finished() || !round.error().empty(); }, &round);
    s.reportLate(round, result.lateNodes);
    if (!done && Clock::now() >= deadline) {
      // Nodes that missed the frame deadline are dropped; their work moves or shows as offline.
      for (std::size_t node : round.awaited()) s.lose(node, "missed the frame deadline", &round);
      deadline = Clock::now() + s.config.timeouts.frame;
    }
  }

  // What this frame cost each node that delivered it is what the next may cost.
  for (std::size_t n : s.synced())
    if (round.delivered(n)) {
      s.nodes[n].expectedWait = s.nodes[n].longestWait;
      s.nodes[n].finishedAFrame = true;
    }
  if (s.strategy->frameDone()) {
    // The barrier: every tile is in (or given up), so the wall swaps at once.
    for (std::size_t n : s.synced())
      if (round.delivered(n)) s.nodes[n].link->send(makeFrame(Swap{result.frame}));
  }

  result.busySeconds.assign(s.nodes.size(), 0.0);
  for (const auto& [node, busy] : round.busySeconds()) result.busySeconds[node] = busy;
  result.tileSeconds.assign(s.nodes.size(), 0.0);
  for (const auto& [node, t] : round.tileSeconds()) result.tileSeconds[node] = t;
  for (const auto& it : round.items()) result.offlineTiles += it.offline ? 1 : 0;
  for (const auto& it : round.items())
    if (it.done || it.offline)
      result.tiles.push_back(
          {it.rect, it.offline ? TileWork::kNoNode : it.node, it.seconds, it.samples, it.rays, it.syncSeconds});
  result.participants = live;
  s.lastWorkload = summarizeWorkload(result.tiles, result.busySeconds, live, s.nodes.size());
  result.reassignedItems = s.reassigned;
  result.assembleSeconds = round.assembleSeconds();
  result.barrierSeconds = round.barrierSeconds();
  if (s.resolver && !result.pixelsKept) {
    for (auto& t : targets) {
      s.resolver->resolve(t);
      for (const auto& name : s.resolveInputs)
        if (std::find(s.options.outputs.begin(), s.options.outputs.end(), name) == s.options.outputs.end())
          t.outputs.erase(name);
    }
  }
  s.strategy->compose(targets, result);
  if (s.wantsWorkload() && !result.image.colour.empty())
    result.image.outputs[std::string(kWorkloadOutput)] =
        drawWorkload(result.tiles, result.image.width, result.image.height);
  return result;
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
    const Node& n = impl_->nodes[i];
    auto [phase, since] = impl_->phaseOf(i, nullptr);
    out.push_back({n.config.address, n.name, n.state, n.applied, n.link->bytesSent(), n.link->bytesReceived(),
                   n.lastError, phase, since, n.lastReport});
  }
  return out;
}

std::size_t ClusterWindow::onlineNodes() const {
  return static_cast<std::size_t>(std::count_if(impl_->nodes.begin(), impl_->nodes.end(), [](const Node& n) {
    return n.state == NodeState::Joined || n.state == NodeState::Synced;
  }));
}

const ClusterConfig& ClusterWindow::config() const { return impl_->config; }

double ClusterWindow::estimatedImbalance() const { return impl_->strategy->imbalance(); }

const FrameWorkload& ClusterWindow::lastWorkload() const { return impl_->lastWorkload; }

}  // namespace tsr::cluster
