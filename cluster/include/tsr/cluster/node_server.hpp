#pragma once
// A render node: accepts clients, authenticates them, and for each keeps a
// replica of the client's scene and the viewports it asked for (created by
// back-end name through the registry). Each client is a separate session:
// a peer that misbehaves is disconnected without touching the others.
#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>

#include "tsr/cluster/node_address.hpp"
#include "tsr/cluster/presenter.hpp"
#include "tsr/med/viewport_registry.hpp"

namespace tsr::cluster {

struct NodeOptions {
  NodeAddress listen;  // port 0 picks a free port
  std::string token;   // empty: no token file given (any client that also has none may connect)
  // Without a token a node serves anyone who can reach it, so it listens
  // only on loopback addresses unless this is set (--insecure).
  bool insecure = false;
  std::string name = "node";
  unsigned threads = 0;  // default "threads" parameter of viewports; 0 leaves it to the back-end
  // What the node does with its wall tiles when the swap barrier releases a
  // frame (null: nothing, and tiles are not kept for it).
  std::shared_ptr<Presenter> presenter;
  std::chrono::milliseconds handshakeTimeout{5000};
  std::chrono::milliseconds idleTimeout{15000};  // clients heartbeat far more often than this
};

// A node asked to listen on a non-loopback address without a token.
class InsecureListenError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class NodeServer {
 public:
  NodeServer(NodeOptions options, const med::ViewportRegistry& registry);
  ~NodeServer();
  NodeServer(const NodeServer&) = delete;
  NodeServer& operator=(const NodeServer&) = delete;

  // Binds and listens; returns the address actually bound. Throws
  // InsecureListenError for a non-loopback address without a token (unless
  // options.insecure), std::system_error (e.g. address in use).
  NodeAddress listen();
  // Makes SIGINT and SIGTERM stop run(); call before listen() so a signal
  // that follows the "listening on" line is never lost.
  void stopOnSignals();
  // Serves on the calling thread until stop().
  void run();
  void stop();  // any thread

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tsr::cluster
