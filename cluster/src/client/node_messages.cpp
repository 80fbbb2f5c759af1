// What the nodes send the client: link events (joined, failed, closed) and
// one handler per message after the handshake.
#include <algorithm>
#include <string>

#include <spdlog/spdlog.h>

#include "client/cluster_window_impl.hpp"
#include "tsr/cluster/protocol_error.hpp"

namespace tsr::cluster {

namespace {
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
}  // namespace

void ClusterWindow::Impl::handle(LinkEvent& e, FrameRound* round) {
  ClusterNode& n = nodes.at(e.node);
  if (e.generation != n.generation) return;
  switch (e.kind) {
    case LinkEvent::Kind::Connected:
      setState(n, NodeState::Joined);
      n.name = e.welcome.nodeName;
      n.applied = 0;
      n.lastReport.reset();
      // Kept even without the back-end: it still mirrors the scene; its renders fail and drop it then.
      if (std::find(e.welcome.backends.begin(), e.welcome.backends.end(), n.config.backend) == e.welcome.backends.end())
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

void ClusterWindow::Impl::receive(std::size_t i, const Message& m, FrameRound* round) {
  switch (m.type) {
    case Applied::kType:
      nodes[i].applied = parse<Applied>(m).version;
      return;
    case RenderTile::kType: {
      RenderTile tile = parse<RenderTile>(m);
      if (!round) return;
      if (const WorkItem* done = round->onTile(i, tile)) {
        strategy->tileDone(*done, tile.seconds);
        ClusterNode& n = nodes[i];
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
      ClusterNode& n = nodes[i];
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

}  // namespace tsr::cluster
