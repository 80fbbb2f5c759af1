#pragma once
// The client's connection to one node: connect with a timeout, handshake,
// then heartbeats and a read loop that turns every message into an inbox
// event. Runs on the client's io thread; the client thread talks to it only
// through start/send/close (posted) and the inbox.
#include <atomic>
#include <memory>

#include "client/link_event.hpp"
#include "protocol/connection.hpp"
#include "tsr/cluster/cluster_config.hpp"

namespace tsr::cluster {

class NodeLink : public std::enable_shared_from_this<NodeLink> {
 public:
  NodeLink(asio::io_context& io, std::size_t node, NodeAddress address, std::string token, Timeouts timeouts,
           Inbox& inbox);
  // Starts connection attempt `generation` (closing any previous one).
  void start(std::uint64_t generation);
  void send(Frame frame);  // any thread; dropped when not connected
  void close();            // any thread
  // Sends `last` (a Bye), then closes once everything queued is written.
  void finish(Frame last);  // any thread
  // A connection attempt or connection is under way (false once it ended).
  bool running() const { return running_ > 0; }
  // Bytes of the messages the client sent through this link (heartbeats aside).
  std::uint64_t bytesSent() const { return bytesSent_; }
  std::uint64_t bytesReceived() const { return bytesReceived_; }

 private:
  asio::awaitable<void> run(std::uint64_t generation);
  asio::awaitable<void> heartbeat(std::shared_ptr<Connection> conn);
  void report(LinkEvent::Kind kind, std::uint64_t generation, std::string reason = {});

  asio::io_context& io_;
  std::size_t node_;
  NodeAddress address_;
  std::string token_;
  Timeouts timeouts_;
  Inbox& inbox_;
  std::shared_ptr<Connection> conn_;  // io thread only
  std::atomic<std::uint64_t> bytesSent_{0}, bytesReceived_{0};
  std::atomic<int> running_{0};  // run() coroutines not yet ended
};

}  // namespace tsr::cluster
