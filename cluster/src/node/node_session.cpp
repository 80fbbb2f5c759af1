#include "node/node_session.hpp"

#include <algorithm>
#include <chrono>

#include <spdlog/spdlog.h>

#include "tsr/cluster/handshake.hpp"
#include "tsr/cluster/pixel_codec.hpp"
#include "tsr/cluster/protocol_error.hpp"
#include "tsr/med/parameters.hpp"
#include "tsr/med/viewport_registry.hpp"
#include "tsr/sg/errors.hpp"
#include "tsr/sg/wire/wire_codec.hpp"

namespace tsr::cluster {

using Kind = ProtocolError::Kind;
using Clock = std::chrono::steady_clock;
// Far below any client's dead-node timeout (its default is 4 s).
constexpr std::chrono::milliseconds kBulkAckInterval{100};

namespace {
std::string peerName(const tcp::socket& s) {
  boost::system::error_code ec;
  auto ep = s.remote_endpoint(ec);
  return ec ? std::string("?") : ep.address().to_string() + ":" + std::to_string(ep.port());
}

// What the client is told about an exception from creating, preparing or
// rendering a viewport (called in a catch block): a missing back-end and
// refused parameters are named, anything else is `otherwise`.
ErrorReport::Kind failureKind(ErrorReport::Kind otherwise) {
  try {
    throw;
  } catch (const med::UnknownBackend&) {
    return ErrorReport::Kind::UnknownBackend;
  } catch (const med::ParameterError&) {
    return ErrorReport::Kind::InvalidParameter;
  } catch (...) {
    return otherwise;
  }
}
}  // namespace

NodeSession::NodeSession(tcp::socket socket, NodeContext& context) : ctx_(context), peer_(peerName(socket)) {
  conn_ = std::make_shared<Connection>(std::move(socket), Sender::Client);
}

NodeSession::~NodeSession() { spdlog::info("session {} ended", peer_); }

void NodeSession::start() {
  conn_->startWatchdog(ctx_.options.handshakeTimeout, ctx_.options.idleTimeout);
  asio::co_spawn(
      conn_->executor(), [self = shared_from_this()] { return self->run(); }, asio::detached);
}

asio::awaitable<void> NodeSession::run() {
  try {
    if (!co_await handshake()) co_return;
    conn_->setIdleLimit(ctx_.options.idleTimeout);
    // The client's heartbeats queue behind a large snapshot in the stream:
    // while one arrives, say we are alive without being asked.
    conn_->onBulkProgress(kBulkAckInterval, [conn = std::weak_ptr<Connection>(conn_)] {
      if (auto c = conn.lock()) c->send(makeFrame(HeartbeatAck{0}));
    });
    spdlog::info("session {} authenticated", peer_);
    while (conn_->isOpen()) {
      Message m = co_await conn_->receive();
      dispatch(m);
    }
  } catch (const ProtocolError& e) {
    spdlog::warn("session {}: {} ({}); disconnecting", peer_, e.what(), name(e.kind()));
    if (conn_->authenticated()) {
      // A client we know gets the reason (a view it cannot render, say);
      // strangers only get the hang-up.
      conn_->send(makeFrame(
          ErrorReport{ErrorReport::Kind::ProtocolViolation, std::string(e.what()).substr(0, kMaxReasonBytes)}));
      conn_->closeAfterFlush();
    } else {
      conn_->close();
    }
  } catch (const boost::system::system_error& e) {
    if (conn_->timedOut())
      spdlog::warn("session {}: peer went quiet; disconnecting", peer_);
    else
      spdlog::info("session {}: {}", peer_, e.code().message());
    conn_->close();
  }
  state_->cancelled = true;  // queued work for this client is skipped
}

asio::awaitable<bool> NodeSession::handshake() {
  Welcome welcome{ctx_.options.name, ctx_.options.threads, ctx_.registry.backends()};
  NodeHandshake hs(ctx_.options.token, welcome);
  NodeHandshake::Step step;
  try {
    Message hello = co_await conn_->receive();
    step = hs.onHello(hello);
  } catch (const ProtocolError& e) {
    if (e.kind() != Kind::VersionMismatch) throw;
    // Say why before hanging up: an old client deserves a readable reason.
    conn_->send(makeFrame(Reject{e.what()}));
    conn_->closeAfterFlush();
    spdlog::warn("session {}: {}", peer_, e.what());
    co_return false;
  }
  conn_->send(step.reply);
  if (step.accepted) {
    Message auth = co_await conn_->receive();
    step = hs.onAuth(auth);
    conn_->send(step.reply);
  }
  if (!step.accepted) {
    spdlog::warn("session {}: {}", peer_, step.reason);
    conn_->closeAfterFlush();
    co_return false;
  }
  conn_->setAuthenticated();
  co_return true;
}

void NodeSession::failFromWorker(ErrorReport::Kind kind, const std::string& reason) {
  spdlog::warn("session {}: {}; disconnecting", peer_, reason);
  state_->cancelled = true;
  asio::post(conn_->executor(), [conn = conn_, kind, reason = reason.substr(0, kMaxReasonBytes)] {
    conn->send(makeFrame(ErrorReport{kind, reason}));
    conn->closeAfterFlush();
  });
}

template <>
void NodeSession::on<Snapshot>(Message& m) {
  onReplicaBytes(m, true);
}

template <>
void NodeSession::on<Changes>(Message& m) {
  onReplicaBytes(m, false);
}

// The change list is the whole payload: decoded where it is applied, not copied.
void NodeSession::onReplicaBytes(Message& m, bool snapshot) {
  // Decoding and applying run on the worker, in order with rendering.
  ctx_.worker.post([self = shared_from_this(), bytes = std::move(m.payload), snapshot] {
    State& st = *self->state_;
    if (st.cancelled) return;
    try {
      sg::ChangeListPtr list = sg::decode(bytes);
      if (list->carriesSnapshot() != snapshot) throw sg::ApplyError("message kind and change list kind differ");
      // A snapshot's first part (or the whole) to a replica that holds a scene.
      if (snapshot && !st.replica->awaitingSnapshot() && st.replica->version() != 0) {
        // A client that resynchronises starts us over.
        st.viewports.clear();
        st.sequences.clear();
        st.replica = std::make_unique<sg::Replica>();
      }
      st.replica->apply(list);
      if (st.replica->awaitingSnapshot()) return;  // more parts follow
      self->conn_->post(makeFrame(Applied{st.replica->version()}));
    } catch (const sg::DecodeError& e) {
      self->failFromWorker(ErrorReport::Kind::SceneRejected, std::string("change list does not decode: ") + e.what());
    } catch (const sg::ApplyError& e) {
      self->failFromWorker(ErrorReport::Kind::SceneRejected, std::string("change list does not apply: ") + e.what());
    }
  });
}

template <>
void NodeSession::on<SetViewports>(Message& m) {
  SetViewports sv = parse<SetViewports>(m);
  // An unknown back-end is the client's configuration error, not an attack:
  // say so now; the replica keeps following, rendering that viewport fails.
  // So is a parameter the back-end does not take, or a bad value: refused
  // now with the table's reason, naming the valid ones.
  for (const auto& v : sv.viewports) {
    if (!ctx_.registry.has(v.backend)) {
      conn_->send(
          makeFrame(ErrorReport{ErrorReport::Kind::UnknownBackend, "this node has no back-end '" + v.backend + "'"}));
      continue;
    }
    try {
      ctx_.registry.capabilities(v.backend).parameters.validate(v.parameters);
    } catch (const med::ParameterError& e) {
      conn_->send(makeFrame(ErrorReport{ErrorReport::Kind::InvalidParameter, e.what()}));
    }
  }
  ctx_.worker.post([self = shared_from_this(), sv = std::move(sv)] {
    State& st = *self->state_;
    st.viewports.clear();
    st.sequences.clear();
    st.settings.clear();
    st.window = sv.window;
    for (const auto& v : sv.viewports) {
      med::ViewportSettings s;
      s.backend = v.backend;
      s.root = v.root;
      s.background = v.background;
      s.parameters = v.parameters;
      if (self->ctx_.options.threads && !s.parameters.has("threads") && self->ctx_.registry.has(s.backend) &&
          self->ctx_.registry.capabilities(s.backend).parameters.declares("threads"))
        s.parameters.set("threads", std::int64_t{self->ctx_.options.threads});
      st.settings[v.id] = std::move(s);
    }
  });
}

template <>
void NodeSession::on<Prepare>(Message& m) {
  Prepare prepare = parse<Prepare>(m);
  ctx_.worker.post([self = shared_from_this(), prepare = std::move(prepare)] {
    State& st = *self->state_;
    if (st.cancelled) return;
    try {
      sg::ChangeListPtr list = sg::decode(prepare.changes);
      if (list->carriesSnapshot() && !st.ahead->awaitingSnapshot()) {
        // The sequence starts over (a node that joins late): its viewports too.
        st.ahead = std::make_unique<sg::Replica>();
        st.sequences.clear();
      }
      st.ahead->apply(list);
      if (st.ahead->awaitingSnapshot()) return;  // the frame's scene is not whole yet
      for (const auto& [id, settings] : st.settings) {
        auto& vp = st.sequences[id];
        if (!vp) vp = self->ctx_.registry.create(settings, st.contexts);
        if (vp->lookahead() == 0) {
          st.sequences.erase(id);  // renders each frame on its own, per rectangle
          continue;
        }
        vp->prepare(*st.ahead, prepare.frame);
      }
    } catch (const sg::DecodeError& e) {
      self->failFromWorker(ErrorReport::Kind::SceneRejected,
                           std::string("change list ahead does not decode: ") + e.what());
    } catch (const sg::ApplyError& e) {
      self->failFromWorker(ErrorReport::Kind::SceneRejected,
                           std::string("change list ahead does not apply: ") + e.what());
    } catch (const std::exception& e) {
      self->failFromWorker(failureKind(ErrorReport::Kind::PrepareFailed),
                           std::string("preparing frame ") + std::to_string(prepare.frame) + " failed: " + e.what());
    }
  });
}

template <>
void NodeSession::on<RenderRequest>(Message& m) {
  RenderRequest request = parse<RenderRequest>(m);
  ctx_.worker.post([self = shared_from_this(), request = std::move(request)] {
    if (self->state_->cancelled) return;
    try {
      render(*self->state_, self->ctx_, request, self->conn_);
    } catch (const std::exception& e) {
      self->failFromWorker(failureKind(ErrorReport::Kind::RenderFailed), std::string("render failed: ") + e.what());
    }
  });
}

void NodeSession::render(State& st, const NodeContext& ctx, const RenderRequest& request,
                         const std::shared_ptr<Connection>& conn) {
  auto started = Clock::now();
  // Viewports of rectangles not asked for again are dropped afterwards: a
  // tile that moved away loses its samples, one that stays keeps them.
  std::map<State::Key, std::unique_ptr<med::Viewport>> used;
  if (request.frame != st.lastFrame) st.backBuffer.clear();
  for (const auto& job : request.jobs) {
    auto settings = st.settings.find(job.viewport);
    if (settings == st.settings.end()) throw std::runtime_error("no viewport " + std::to_string(job.viewport));
    const auto sequence = st.sequences.find(job.viewport);
    for (const auto& rect : job.rects) {
      if (st.cancelled) return;
      med::Viewport* vp = nullptr;
      if (sequence != st.sequences.end()) {
        vp = sequence->second.get();
      } else {
        State::Key key{job.viewport, rect.x0, rect.y0, rect.x1, rect.y1};
        auto& held = used[key];
        if (!held) {
          if (auto kept = st.viewports.find(key); kept != st.viewports.end())
            held = std::move(kept->second);
          else
            held = ctx.registry.create(settings->second, st.contexts);
        }
        vp = held.get();
      }
      med::FrameBuffer fb;
      med::RenderControl control;
      control.cancel = &st.cancelled;
      control.outputs = job.outputs;
      control.resolve = job.resolve;
      control.frame = request.sequenceFrame;
      auto t0 = Clock::now();
      const med::RenderStats stats = vp->render(*st.replica, job.view.cropped(rect), fb, control);
      RenderTile tile;
      tile.frame = request.frame;
      tile.viewport = job.viewport;
      tile.rect = rect;
      tile.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
      tile.samples = std::min(stats.samples, kMaxTileSamples);
      tile.rays = std::min(stats.rays, kMaxTileRays);
      tile.syncSeconds = std::clamp(stats.syncSeconds, 0.0, tile.seconds);
      tile.outputs = job.outputs;
      if (request.compression == Compression::Kept) {
        tile.compression = Compression::Kept;
      } else {
        EncodedPixels px = encodePixels(fb, request.compression, job.outputs);
        tile.compression = px.compression;
        tile.pixels = std::move(px.bytes);
      }
      if (ctx.options.presenter) st.backBuffer.push_back({rect, std::move(fb)});
      conn->post(makeFrame(tile));
    }
  }
  if (request.frame == st.lastFrame) used.merge(st.viewports);  // a second request in one frame (tiles taken over)
  st.viewports = std::move(used);
  st.lastFrame = request.frame;
  double busy = std::chrono::duration<double>(Clock::now() - started).count();
  conn->post(makeFrame(FrameDone{request.frame, busy}));
}

template <>
void NodeSession::on<Swap>(Message& m) {
  // The wall's barrier released: show the tiles rendered for this frame.
  Swap swap = parse<Swap>(m);
  ctx_.worker.post([self = shared_from_this(), swap] {
    const State& st = *self->state_;
    if (st.lastFrame != swap.frame || !self->ctx_.options.presenter) return;
    spdlog::debug("session {}: presenting frame {}", self->peer_, swap.frame);
    self->ctx_.options.presenter->present(swap.frame, st.backBuffer, st.window);
  });
}

template <>
void NodeSession::on<HashQuery>(Message& m) {
  HashQuery q = parse<HashQuery>(m);
  ctx_.worker.post([self = shared_from_this(), q] {
    const sg::Replica& r = *self->state_->replica;
    self->conn_->post(makeFrame(HashReply{q.token, r.version(), r.scene().contentHash()}));
  });
}

template <>
void NodeSession::on<Heartbeat>(Message& m) {
  conn_->send(makeFrame(HeartbeatAck{parse<Heartbeat>(m).sequence}));
}

template <>
void NodeSession::on<Bye>(Message& m) {
  parse<Bye>(m);
  conn_->closeAfterFlush();
}

// Every message a client sends after the handshake goes to its on<M>; the
// handshake's messages and the node's own are refused.
void NodeSession::dispatch(Message& m) {
  bool known = Messages::visit(m.type, [&]<class M>() {
    if constexpr (M::kSpec.sender == Sender::Client && !M::kSpec.beforeAuth)
      on<M>(m);
    else
      throw ProtocolError(Kind::Unexpected, std::string(M::kSpec.name) + " after the handshake");
  });
  if (!known) throw ProtocolError(Kind::UnknownType, "unknown message type " + std::to_string(int(m.type)));
}

}  // namespace tsr::cluster
