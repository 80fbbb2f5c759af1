#include "client/node_link.hpp"

#include <spdlog/spdlog.h>

#include "tsr/cluster/handshake.hpp"
#include "tsr/cluster/protocol_error.hpp"

namespace tsr::cluster {

NodeLink::NodeLink(asio::io_context& io, std::size_t node, NodeAddress address, std::string token, Timeouts timeouts,
                   Inbox& inbox)
    : io_(io),
      node_(node),
      address_(std::move(address)),
      token_(std::move(token)),
      timeouts_(timeouts),
      inbox_(inbox) {}

void NodeLink::start(std::uint64_t generation) {
  asio::post(io_, [self = shared_from_this(), generation] {
    if (self->conn_) self->conn_->close();
    self->conn_.reset();
    asio::co_spawn(self->io_, self->run(generation), asio::detached);
  });
}

void NodeLink::send(Frame frame) {
  bytesSent_ += frame->size();
  asio::post(io_, [self = shared_from_this(), f = std::move(frame)]() mutable {
    if (self->conn_) self->conn_->send(std::move(f));
  });
}

void NodeLink::close() {
  asio::post(io_, [self = shared_from_this()] {
    if (self->conn_) self->conn_->close();
  });
}

void NodeLink::finish(Frame last) {
  asio::post(io_, [self = shared_from_this(), f = std::move(last)]() mutable {
    if (!self->conn_) return;
    self->conn_->send(std::move(f));
    self->conn_->closeAfterFlush();
  });
}

void NodeLink::report(LinkEvent::Kind kind, std::uint64_t generation, std::string reason) {
  LinkEvent e;
  e.kind = kind;
  e.node = node_;
  e.generation = generation;
  e.reason = std::move(reason);
  inbox_.push(std::move(e));
}

asio::awaitable<void> NodeLink::run(std::uint64_t generation) {
  ++running_;
  struct Ended {
    std::atomic<int>& running;
    ~Ended() { --running; }
  } ended{running_};
  auto conn = std::make_shared<Connection>(tcp::socket(io_), Sender::Node);
  conn_ = conn;
  bool connected = false;
  try {
    // The watchdog bounds connecting and the handshake as well: nothing
    // arrives, the socket closes, the awaits below fail.
    conn->startWatchdog(timeouts_.connect, timeouts_.deadAfter);
    tcp::resolver resolver(io_);
    auto endpoints = co_await resolver.async_resolve(address_.host, std::to_string(address_.port), asio::use_awaitable);
    co_await asio::async_connect(conn->socket(), endpoints, asio::use_awaitable);
    boost::system::error_code ignored;
    conn->socket().set_option(tcp::no_delay(true), ignored);
    ClientHandshake hs(token_, "tessera-client");
    conn->send(hs.hello());
    conn->send(hs.onChallenge(co_await conn->receive()));
    Welcome welcome = hs.onWelcome(co_await conn->receive());
    conn->setAuthenticated();
    conn->setIdleLimit(timeouts_.deadAfter);
    connected = true;
    LinkEvent e;
    e.kind = LinkEvent::Kind::Connected;
    e.node = node_;
    e.generation = generation;
    e.welcome = std::move(welcome);
    inbox_.push(std::move(e));
    asio::co_spawn(io_, heartbeat(conn), asio::detached);
    for (;;) {
      LinkEvent m;
      m.kind = LinkEvent::Kind::Received;
      m.node = node_;
      m.generation = generation;
      m.message = co_await conn->receive();
      bytesReceived_ += kFrameHeaderBytes + m.message.payload.size();
      inbox_.push(std::move(m));
    }
  } catch (const ProtocolError& e) {
    conn->close();
    report(connected ? LinkEvent::Kind::Closed : LinkEvent::Kind::Failed, generation, e.what());
  } catch (const boost::system::system_error& e) {
    conn->close();
    std::string why = conn->timedOut() ? "node went quiet" : e.code().message();
    report(connected ? LinkEvent::Kind::Closed : LinkEvent::Kind::Failed, generation, why);
  }
}

asio::awaitable<void> NodeLink::heartbeat(std::shared_ptr<Connection> conn) {
  asio::steady_timer timer(io_);
  std::uint64_t sequence = 0;
  while (conn->isOpen()) {
    conn->send(makeFrame(Heartbeat{++sequence}));
    timer.expires_after(timeouts_.heartbeat);
    co_await timer.async_wait(asio::use_awaitable);
  }
}

}  // namespace tsr::cluster
