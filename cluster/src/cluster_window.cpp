#include "tsr/cluster/cluster_window.hpp"

#include <algorithm>
#include <optional>
#include <thread>

#include <spdlog/spdlog.h>

#include "frame_round.hpp"
#include "node_link.hpp"
#include "tsr/cluster/protocol_error.hpp"
#include "tsr/cluster/tile_balancer.hpp"
#include "tsr/cluster/wall_layout.hpp"
#include "tsr/med/compositing.hpp"
#include "tsr/sg/wire_codec.hpp"

namespace tsr::cluster {

using Clock = std::chrono::steady_clock;

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
  std::string lastError;
};
}  // namespace

struct ClusterWindow::Impl {
  ClusterConfig config;
  ClientOptions options;
  asio::io_context io;
  asio::executor_work_guard<asio::io_context::executor_type> work{io.get_executor()};
  std::thread thread;
  Inbox inbox;
  std::vector<Node> nodes;

  std::optional<TileBalancer> balancer;
  std::vector<med::PixelRect> tiles;
  std::uint32_t tilesFor[2] = {0, 0};
  FrameRound* round = nullptr;  // while render() runs
  std::size_t reassigned = 0;
  std::vector<ReplicaHash>* hashes = nullptr;
  std::uint64_t hashToken = 0;
  std::uint64_t frame = 0;
  float eyeSeparation, zeroParallax;
  sg::ContainerId root = sg::kNoContainer, background = sg::kNoContainer;
  // The local viewport that resolves assembled frames, and what it needs.
  med::ContextPool resolverContexts;
  std::unique_ptr<med::Viewport> resolver;
  std::vector<std::string> resolveInputs;
  std::vector<std::string> resolveOutputs;
  std::string renderError;  // a node's report that it cannot render this frame

  Impl(ClusterConfig c, ClientOptions o) : config(std::move(c)), options(std::move(o)) {
    eyeSeparation = config.stereo.eyeSeparation.value_or(0.065f);
    zeroParallax = config.stereo.zeroParallax.value_or(5.0f);
    thread = std::thread([this] { io.run(); });
  }
  ~Impl() {
    for (auto& n : nodes)
      if (n.link) {
        n.link->send(makeFrame(Bye{}));
        n.link->close();
      }
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

  void startConnecting(std::size_t i) {
    Node& n = nodes[i];
    n.state = NodeState::Connecting;
    n.link->start(++n.generation);
  }

  void retryOffline() {
    auto now = Clock::now();
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (nodes[i].state == NodeState::Offline && now >= nodes[i].retryAt) startConnecting(i);
  }

  // Sets a node offline and lets the running frame give its work away.
  void lose(std::size_t i, const std::string& why) {
    Node& n = nodes[i];
    if (n.state == NodeState::Offline) return;
    bool wasIn = n.state == NodeState::Synced;
    spdlog::warn("node {} ({}) lost: {}", n.config.address.text(), n.name, why);
    n.link->close();
    ++n.generation;  // events of the old connection no longer count
    n.state = NodeState::Offline;
    n.lastError = why;
    n.retryAt = Clock::now() + config.timeouts.retry;
    if (round) round->forget(i);
    if (wasIn && round) takeOver(i);
  }

  std::vector<std::size_t> synced() const {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (nodes[i].state == NodeState::Synced) out.push_back(i);
    return out;
  }

  // The work of a lost node: another node's in cooperative and stereo mode
  // (sent within this frame), the offline fill on a wall.
  void takeOver(std::size_t lost) {
    std::vector<std::size_t> pending = round->pendingOf(lost);
    if (pending.empty()) return;
    if (config.mode == ClusterMode::Tiled) {
      for (std::size_t item : pending) round->giveUp(item, config.wall.offlineColour);
      return;
    }
    std::vector<std::size_t> live = synced();
    if (live.empty()) return;  // render() notices and throws
    if (balancer) balancer->removeNode(lost);
    std::map<std::size_t, std::vector<std::size_t>> handed;
    for (std::size_t k = 0; k < pending.size(); ++k) {
      const WorkItem& it = round->items()[pending[k]];
      std::size_t to = (balancer && it.tile != TileBalancer::kNone) ? balancer->owner(it.tile) : live[k % live.size()];
      round->reassign(pending[k], to);
      handed[to].push_back(pending[k]);
    }
    for (auto& [to, items] : handed) {
      nodes[to].link->send(round->request(items));
      round->sent(to);
      reassigned += items.size();
    }
  }

  void handle(LinkEvent& e) {
    Node& n = nodes.at(e.node);
    if (e.generation != n.generation) return;
    switch (e.kind) {
      case LinkEvent::Kind::Connected:
        n.state = NodeState::Joined;
        n.name = e.welcome.nodeName;
        n.applied = 0;
        // Kept even without the back-end: it still mirrors the scene; its renders fail and drop it then.
        if (std::find(e.welcome.backends.begin(), e.welcome.backends.end(), n.config.backend) == e.welcome.backends.end())
          spdlog::warn("node {} has no back-end '{}'", n.config.address.text(), n.config.backend);
        spdlog::info("node {} ({}) joined", n.config.address.text(), n.name);
        return;
      case LinkEvent::Kind::Failed:
        if (n.lastError != e.reason) spdlog::warn("node {}: cannot connect: {}", n.config.address.text(), e.reason);
        n.state = NodeState::Offline;
        n.lastError = e.reason;
        n.retryAt = Clock::now() + config.timeouts.retry;
        return;
      case LinkEvent::Kind::Closed:
        return lose(e.node, e.reason);
      case LinkEvent::Kind::Received:
        try {
          receive(e.node, e.message);
        } catch (const ProtocolError& err) {
          lose(e.node, std::string("protocol violation: ") + err.what());
        }
        return;
    }
  }

  // One handler per message a node sends.
  void receive(std::size_t i, const Message& m) {
    switch (m.type) {
      case MessageType::Applied: nodes[i].applied = parse<Applied>(m).version; return;
      case MessageType::RenderTile: {
        RenderTile tile = parse<RenderTile>(m);
        if (!round) return;
        const WorkItem* done = round->onTile(i, tile);
        if (done && balancer && done->tile != TileBalancer::kNone) balancer->record(done->tile, tile.seconds);
        return;
      }
      case MessageType::FrameDone:
        if (round) round->onDone(i, parse<FrameDone>(m));
        return;
      case MessageType::HashReply: {
        HashReply r = parse<HashReply>(m);
        if (hashes && r.token == hashToken) hashes->push_back({i, r.version, r.hash});
        return;
      }
      case MessageType::HeartbeatAck: parse<HeartbeatAck>(m); return;
      case MessageType::Error:
        nodes[i].lastError = parse<ErrorReport>(m).reason;
        spdlog::warn("node {}: {}", nodes[i].config.address.text(), nodes[i].lastError);
        // A node that cannot render the frame (a bad parameter, an output its
        // back-end lacks) would fail the same way on every node it moves to.
        if (round && nodes[i].lastError.rfind("render failed", 0) == 0 && renderError.empty())
          renderError = "node " + nodes[i].config.address.text() + ": " + nodes[i].lastError;
        return;
      default: throw ProtocolError(ProtocolError::Kind::Unexpected, std::string(name(m.type)) + " after the handshake");
    }
  }

  // Handles events until `done` holds or the deadline passes.
  template <class Done>
  bool pump(Clock::time_point deadline, Done done) {
    while (!done()) {
      auto e = inbox.pop(deadline);
      if (!e) return done();
      handle(*e);
    }
    return true;
  }
  void drain() {
    pump(Clock::now(), [] { return false; });
  }

  std::vector<WorkItem> plan(const med::View& view, std::vector<med::FrameBuffer>& targets,
                             const std::vector<std::size_t>& live) {
    std::vector<WorkItem> items;
    switch (config.mode) {
      case ClusterMode::Cooperative: {
        if (!balancer || tilesFor[0] != view.width || tilesFor[1] != view.height) {
          tiles = tileGrid(view.width, view.height, config.cooperative.tileSize);
          balancer.emplace(tiles.size(), config.cooperative.tolerance, config.cooperative.maxMovesPerFrame);
          tilesFor[0] = view.width;
          tilesFor[1] = view.height;
        }
        balancer->setNodes(live);
        targets.emplace_back(view.width, view.height);
        for (std::size_t t = 0; t < tiles.size(); ++t) items.push_back({0, view, tiles[t], 0, t, balancer->owner(t)});
        break;
      }
      case ClusterMode::Tiled: {
        auto rects = wallLayout(view.width, view.height, config.wall.columns, config.wall.rows, config.wall.bezel);
        targets.emplace_back(view.width, view.height);
        for (std::size_t t = 0; t < rects.size(); ++t) items.push_back({0, view, rects[t], 0, TileBalancer::kNone, t});
        break;
      }
      case ClusterMode::Stereo: {
        targets.emplace_back(view.width, view.height);
        targets.emplace_back(view.width, view.height);
        // Node 0 takes the left eye and node 1 the right, as configured,
        // when they are there; otherwise whoever is.
        auto pick = [&](std::size_t preferred, std::size_t k) {
          return std::find(live.begin(), live.end(), preferred) != live.end() ? preferred : live[k % live.size()];
        };
        med::View l = view.eye(med::Eye::Left, eyeSeparation, zeroParallax);
        med::View r = view.eye(med::Eye::Right, eyeSeparation, zeroParallax);
        items.push_back({0, l, l.region, 0, TileBalancer::kNone, pick(0, 0)});
        items.push_back({1, r, r.region, 1, TileBalancer::kNone, pick(1, 1)});
        break;
      }
    }
    return items;
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
      if (!resolver || !has(resolveOutputs, name)) outputs.push_back(name);
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
      if (!has(held, name)) held.push_back(name);
    for (auto& t : targets)
      for (const auto& name : held) t.outputs[name].assign(t.colour.size(), glm::vec4(0.0f));
  }

  Frame viewportsFor(const Node& n) const {
    SetViewports sv;
    std::uint32_t count = config.mode == ClusterMode::Stereo ? 2 : 1;
    for (std::uint32_t id = 0; id < count; ++id) sv.viewports.push_back({id, n.config.backend, root, background, n.config.parameters});
    return makeFrame(sv);
  }
};

ClusterWindow::ClusterWindow(ClusterConfig config, ClientOptions options)
    : impl_(std::make_unique<Impl>(std::move(config), std::move(options))) {
  impl_->config.validate();
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
    if (follows) {
      if (!changes) changes = frameFromPayload(MessageType::Changes, sg::encode(*delta));
      n.link->send(changes);
    } else if (n.state == NodeState::Synced || n.state == NodeState::Joined) {
      // A new node, or one that missed a list: it starts over from the whole scene.
      if (!snapshot) snapshot = frameFromPayload(MessageType::Snapshot, sg::encode(*scene.snapshot()));
      n.link->send(snapshot);
      if (n.state == NodeState::Joined) n.link->send(s.viewportsFor(n));
      n.state = NodeState::Synced;
    } else {
      continue;
    }
    n.sentVersion = scene.version();
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
  std::vector<ReplicaHash> out;
  s.hashes = &out;
  ++s.hashToken;
  std::vector<std::size_t> asked = s.synced();
  for (std::size_t i : asked) s.nodes[i].link->send(makeFrame(HashQuery{s.hashToken}));
  s.pump(Clock::now() + timeout, [&] {
    return std::all_of(asked.begin(), asked.end(), [&](std::size_t i) {
      return s.nodes[i].state != NodeState::Synced ||
             std::any_of(out.begin(), out.end(), [&](const ReplicaHash& h) { return h.node == i; });
    });
  });
  s.hashes = nullptr;
  return out;
}

ClusterFrame ClusterWindow::render(const med::View& view) {
  Impl& s = *impl_;
  view.validate();
  s.drain();
  std::vector<std::size_t> live = s.synced();
  if (live.empty() && s.config.mode != ClusterMode::Tiled) throw ClusterError("no cluster node is online");

  ClusterFrame result;
  result.frame = ++s.frame;
  std::vector<med::FrameBuffer> targets;
  std::vector<WorkItem> items = s.plan(view, targets, live);
  s.makeResolver();
  s.askOutputs(items, targets);
  FrameRound round(result.frame, std::move(items), targets, s.config.compression);
  s.round = &round;
  s.reassigned = 0;
  struct Clear {
    Impl& s;
    ~Clear() { s.round = nullptr; }
  } clear{s};

  for (std::size_t i = 0; i < round.items().size(); ++i)
    if (s.nodes[round.items()[i].node].state != NodeState::Synced) round.giveUp(i, s.config.wall.offlineColour);
  for (auto& [node, its] : round.pendingByNode()) {
    s.nodes[node].link->send(round.request(its));
    round.sent(node);
  }

  auto deadline = Clock::now() + s.config.timeouts.frame;
  s.renderError.clear();
  while (!round.finished()) {
    if (!s.renderError.empty()) throw ClusterError(s.renderError);
    if (s.config.mode != ClusterMode::Tiled && s.synced().empty()) throw ClusterError("every cluster node was lost during the frame");
    if (!s.pump(deadline, [&] { return round.finished() || !s.renderError.empty(); })) {
      // Nodes that missed the frame deadline are dropped; their work moves or shows as offline.
      for (std::size_t node : round.awaited()) s.lose(node, "missed the frame deadline");
      deadline = Clock::now() + s.config.timeouts.frame;
    }
  }

  if (s.config.mode == ClusterMode::Tiled) {
    // The barrier: every tile is in (or given up), so the wall swaps at once.
    for (std::size_t n : s.synced())
      if (round.delivered(n)) s.nodes[n].link->send(makeFrame(Swap{result.frame}));
  }
  if (s.balancer && s.config.mode == ClusterMode::Cooperative) s.balancer->rebalance();

  result.busySeconds.assign(s.nodes.size(), 0.0);
  for (const auto& [node, busy] : round.busySeconds()) result.busySeconds[node] = busy;
  result.tileSeconds.assign(s.nodes.size(), 0.0);
  for (const auto& [node, t] : round.tileSeconds()) result.tileSeconds[node] = t;
  for (const auto& it : round.items()) result.offlineTiles += it.offline ? 1 : 0;
  result.reassignedItems = s.reassigned;
  if (s.resolver) {
    for (auto& t : targets) {
      s.resolver->resolve(t);
      for (const auto& name : s.resolveInputs)
        if (std::find(s.options.outputs.begin(), s.options.outputs.end(), name) == s.options.outputs.end())
          t.outputs.erase(name);
    }
  }
  if (s.config.mode == ClusterMode::Stereo) {
    result.left = std::move(targets[0]);
    result.right = std::move(targets[1]);
    result.image = s.config.stereo.compose == StereoCompose::Anaglyph ? med::anaglyph(result.left, result.right)
                                                                      : med::sideBySide(result.left, result.right);
  } else {
    result.image = std::move(targets[0]);
  }
  return result;
}

void ClusterWindow::setEyes(float separation, float zeroParallax) {
  // The config's values, where it gives them, win over the application's.
  impl_->eyeSeparation = impl_->config.stereo.eyeSeparation.value_or(separation);
  impl_->zeroParallax = impl_->config.stereo.zeroParallax.value_or(zeroParallax);
}

std::vector<NodeStatus> ClusterWindow::status() const {
  std::vector<NodeStatus> out;
  for (const auto& n : impl_->nodes)
    out.push_back({n.config.address, n.name, n.state, n.applied, n.link->bytesSent(), n.lastError});
  return out;
}

std::size_t ClusterWindow::onlineNodes() const {
  return static_cast<std::size_t>(std::count_if(impl_->nodes.begin(), impl_->nodes.end(), [](const Node& n) {
    return n.state == NodeState::Joined || n.state == NodeState::Synced;
  }));
}

const ClusterConfig& ClusterWindow::config() const { return impl_->config; }

double ClusterWindow::estimatedImbalance() const { return impl_->balancer ? impl_->balancer->imbalance() : 1.0; }

}  // namespace tsr::cluster
