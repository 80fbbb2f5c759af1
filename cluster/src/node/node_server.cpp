#include "tsr/cluster/node_server.hpp"

#include <csignal>
#include <optional>
#include <system_error>

#include <spdlog/spdlog.h>

#include "node/node_session.hpp"

namespace tsr::cluster {

struct NodeServer::Impl {
  Impl(NodeOptions o, const med::ViewportRegistry& registry) : context{std::move(o), registry, worker}, acceptor(io) {}

  // A failed accept (out of file descriptors under a flood of connections,
  // a connection reset before it was taken) must not end the loop: the node
  // would never take a client again. It pauses briefly, so that sessions
  // can close and free descriptors, and accepts on.
  asio::awaitable<void> accept() {
    asio::steady_timer pause(io);
    for (;;) {
      boost::system::error_code ec;
      tcp::socket socket = co_await acceptor.async_accept(asio::redirect_error(asio::use_awaitable, ec));
      if (!ec) {
        std::make_shared<NodeSession>(std::move(socket), context)->start();
        continue;
      }
      if (ec == asio::error::operation_aborted || !acceptor.is_open()) co_return;
      // Accept errors are errno values; std's category names them (Boost
      // 1.74's error_category fails UBSan's vptr check in message()).
      spdlog::warn("accept: {}; accepting again in 100 ms", std::system_category().message(ec.value()));
      pause.expires_after(std::chrono::milliseconds(100));
      co_await pause.async_wait(asio::redirect_error(asio::use_awaitable, ec));
    }
  }

  // Declared first so it is destroyed last: sessions' queued jobs refer to
  // the io context only through their connections.
  asio::io_context io;
  RenderWorker worker;
  NodeContext context;
  tcp::acceptor acceptor;
  std::optional<asio::signal_set> signals;
};

NodeServer::NodeServer(NodeOptions options, const med::ViewportRegistry& registry)
    : impl_(std::make_unique<Impl>(std::move(options), registry)) {}

NodeServer::~NodeServer() = default;

NodeAddress NodeServer::listen() {
  const NodeAddress& want = impl_->context.options.listen;
  tcp::resolver resolver(impl_->io);
  auto results =
      resolver.resolve(want.host, std::to_string(want.port), tcp::resolver::passive | tcp::resolver::numeric_service);
  tcp::endpoint ep = results.begin()->endpoint();
  const NodeOptions& o = impl_->context.options;
  if (o.token.empty() && !o.insecure && !ep.address().is_loopback())
    throw InsecureListenError("refusing to listen on " + want.host + " (" + ep.address().to_string() +
                              ") without --token-file: any client that reaches it could render on this node; "
                              "give --token-file FILE, or --insecure to accept that");
  if (o.token.empty())
    spdlog::warn("no token file given: any client {} without a token may connect",
                 ep.address().is_loopback() ? "on this machine" : "that reaches " + ep.address().to_string());
  auto& a = impl_->acceptor;
  a.open(ep.protocol());
  a.set_option(tcp::acceptor::reuse_address(true));
  a.bind(ep);
  a.listen();
  tcp::endpoint bound = a.local_endpoint();
  asio::co_spawn(impl_->io, impl_->accept(), [](const std::exception_ptr& e) {
    if (!e) return;
    try {
      std::rethrow_exception(e);
    } catch (const boost::system::system_error& err) {
      if (err.code() != asio::error::operation_aborted) spdlog::error("accept: {}", err.what());
    }
  });
  return {want.host, bound.port()};
}

void NodeServer::stopOnSignals() {
  impl_->signals.emplace(impl_->io, SIGINT, SIGTERM);
  impl_->signals->async_wait([this](boost::system::error_code ec, int sig) {
    if (!ec) spdlog::info("signal {}: stopping", sig);
    stop();
  });
}

void NodeServer::run() { impl_->io.run(); }

void NodeServer::stop() {
  asio::post(impl_->io, [this] { impl_->io.stop(); });
}

}  // namespace tsr::cluster
