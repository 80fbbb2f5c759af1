// The client's nodes and their sessions: added, connected, retried, lost
// (their work taken over within the frame), and the viewports they render.
#include <algorithm>
#include <chrono>
#include <thread>

#include <spdlog/spdlog.h>

#include "client/cluster_window_impl.hpp"

namespace tsr::cluster {

ClusterWindow::Impl::Impl(ClusterConfig c, ClientOptions o) : config(std::move(c)), options(std::move(o)) {
  strategy = makeFrameStrategy(config);
  eyes.separation = config.stereo.eyeSeparation.value_or(eyes.separation);
  eyes.zeroParallax = config.stereo.zeroParallax.value_or(eyes.zeroParallax);
  thread = std::thread([this] { io.run(); });
}

ClusterWindow::Impl::~Impl() {
  // What is queued (the last frame's Swap among it) goes out before the
  // Bye; a node that does not take it within a moment is closed anyway.
  for (auto& n : nodes)
    if (n.link) n.link->finish(makeFrame(Bye{}));
  auto until = Clock::now() + std::chrono::milliseconds(500);
  while (Clock::now() < until &&
         std::any_of(nodes.begin(), nodes.end(), [](const ClusterNode& n) { return n.link && n.link->running(); }))
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  for (auto& n : nodes)
    if (n.link) n.link->close();
  work.reset();
  io.stop();
  thread.join();
}

std::size_t ClusterWindow::Impl::add(NodeConfig c) {
  ClusterNode n;
  n.config = std::move(c);
  nodes.push_back(std::move(n));
  std::size_t i = nodes.size() - 1;
  nodes[i].link = std::make_shared<NodeLink>(io, i, nodes[i].config.address, options.token, config.timeouts, inbox);
  return i;
}

void ClusterWindow::Impl::setState(ClusterNode& n, NodeState state) {
  if (n.state != state) n.stateSince = Clock::now();
  if (state == NodeState::Joined || state == NodeState::Offline) {  // a new session
    n.viewportsSent = false;
    n.finishedAFrame = false;
  }
  n.state = state;
}

void ClusterWindow::Impl::startConnecting(std::size_t i) {
  ClusterNode& n = nodes[i];
  setState(n, NodeState::Connecting);
  n.link->start(++n.generation);
}

void ClusterWindow::Impl::retryOffline() {
  auto now = Clock::now();
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].state == NodeState::Offline && now >= nodes[i].retryAt) startConnecting(i);
}

void ClusterWindow::Impl::lose(std::size_t i, const std::string& why, FrameRound* round) {
  ClusterNode& n = nodes[i];
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

std::vector<std::size_t> ClusterWindow::Impl::synced() const {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].state == NodeState::Synced) out.push_back(i);
  return out;
}

void ClusterWindow::Impl::takeOver(FrameRound& round, std::size_t lost) {
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

Frame ClusterWindow::Impl::viewportsFor(const ClusterNode& n) const {
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

}  // namespace tsr::cluster
