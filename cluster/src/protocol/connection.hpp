#pragma once
// One framed TCP connection, used by both sides. Everything runs on the
// io thread; other threads hand frames over with post(). Reads check the
// header (magic, version, type, who may send it, whether it is allowed
// before authentication, its size) before reading or allocating the
// payload; a watchdog closes the socket when the peer goes quiet or stops
// reading what we write. Bulk counts as life: every piece of a payload that
// arrives, and every piece of ours the peer takes, resets the clocks, so a
// large snapshot or tile on a slow link is not mistaken for a dead peer.
#include <atomic>
#include <chrono>
#include <deque>
#include <functional>
#include <memory>

#include "protocol/asio.hpp"
#include "tsr/cluster/messages.hpp"

namespace tsr::cluster {

class Connection : public std::enable_shared_from_this<Connection> {
 public:
  using Clock = std::chrono::steady_clock;

  // `peer` is the side whose messages this connection receives.
  Connection(tcp::socket socket, Sender peer);

  // Reads one message; throws ProtocolError or boost::system::system_error.
  asio::awaitable<Message> receive();
  void setAuthenticated() { authenticated_ = true; }
  bool authenticated() const { return authenticated_; }

  void send(Frame frame);  // io thread only
  void post(Frame frame);  // any thread
  // Sends what is queued, then closes (a Reject before hanging up).
  void closeAfterFlush();
  void close();
  bool isOpen() const { return open_; }

  // Closes when nothing arrived for `idle`, or a write made no progress for `writeStall`.
  void startWatchdog(std::chrono::milliseconds idle, std::chrono::milliseconds writeStall);
  void setIdleLimit(std::chrono::milliseconds idle) { idle_ = idle; }
  bool timedOut() const { return timedOut_; }
  // Called (io thread) at most once per `interval` while a payload is still
  // arriving: the receiver of bulk tells the sender it is alive, since the
  // sender's heartbeats wait behind the bulk in the same stream.
  void onBulkProgress(std::chrono::milliseconds interval, std::function<void()> f) {
    progressInterval_ = interval;
    onProgress_ = std::move(f);
  }

  std::uint64_t bytesSent() const { return bytesSent_; }
  std::uint64_t bytesReceived() const { return bytesReceived_; }
  tcp::socket& socket() { return socket_; }
  asio::any_io_executor executor() { return socket_.get_executor(); }

 private:
  void writeNext();
  void received(std::size_t bytes);
  asio::awaitable<void> watchdog();

  tcp::socket socket_;
  Sender peer_;
  bool authenticated_ = false;
  bool open_ = true;
  bool writing_ = false;
  bool closeAfterFlush_ = false;
  bool timedOut_ = false;
  std::deque<Frame> queue_;
  Clock::time_point lastReceived_ = Clock::now();
  Clock::time_point lastWritten_ = Clock::now();
  std::chrono::milliseconds idle_{0};
  std::chrono::milliseconds writeStall_{0};
  std::size_t written_ = 0;  // of the queue's front frame
  std::chrono::milliseconds progressInterval_{0};
  std::function<void()> onProgress_;
  Clock::time_point lastProgress_ = Clock::now();
  std::atomic<std::uint64_t> bytesSent_{0};
  std::atomic<std::uint64_t> bytesReceived_{0};
};

}  // namespace tsr::cluster
