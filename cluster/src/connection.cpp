#include "connection.hpp"

#include <algorithm>
#include <array>

#include "tsr/cluster/frame_header.hpp"
#include "tsr/cluster/protocol_error.hpp"

namespace tsr::cluster {

using Kind = ProtocolError::Kind;

Connection::Connection(tcp::socket socket, Sender peer) : socket_(std::move(socket)), peer_(peer) {
  boost::system::error_code ignored;
  socket_.set_option(tcp::no_delay(true), ignored);
}

asio::awaitable<Message> Connection::receive() {
  std::array<std::uint8_t, kFrameHeaderBytes> header;
  co_await asio::async_read(socket_, asio::buffer(header), asio::use_awaitable);
  lastReceived_ = Clock::now();
  bytesReceived_ += header.size();
  FrameHeader h = decodeFrameHeader(header);
  const MessageSpec& s = spec(h.type);
  if (s.sender != peer_)
    throw ProtocolError(Kind::Unexpected, std::string(s.name) + " may not be sent by this side");
  if (!authenticated_ && !s.beforeAuth)
    throw ProtocolError(Kind::Unexpected, std::string(s.name) + " before the handshake finished");
  Message m;
  m.type = h.type;
  // Grow with the bytes that actually arrive, so a large announced length
  // costs nothing until the peer sends that much.
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  while (m.payload.size() < h.length) {
    std::size_t have = m.payload.size();
    std::size_t next = std::min<std::size_t>(h.length - have, kChunk);
    m.payload.resize(have + next);
    co_await asio::async_read(socket_, asio::buffer(m.payload.data() + have, next), asio::use_awaitable);
    lastReceived_ = Clock::now();
    bytesReceived_ += next;
  }
  co_return m;
}

void Connection::send(Frame frame) {
  if (!open_ || closeAfterFlush_) return;
  queue_.push_back(std::move(frame));
  if (!writing_) {
    lastWritten_ = Clock::now();  // the stall clock starts with this write
    writeNext();
  }
}

void Connection::post(Frame frame) {
  asio::post(socket_.get_executor(), [self = shared_from_this(), f = std::move(frame)]() mutable { self->send(std::move(f)); });
}

void Connection::closeAfterFlush() {
  if (!writing_) return close();
  closeAfterFlush_ = true;
}

void Connection::close() {
  if (!open_) return;
  open_ = false;
  boost::system::error_code ignored;
  socket_.shutdown(tcp::socket::shutdown_both, ignored);
  socket_.close(ignored);
  queue_.clear();
}

void Connection::writeNext() {
  writing_ = true;
  if (queue_.empty()) {
    writing_ = false;
    if (closeAfterFlush_) close();
    return;
  }
  asio::async_write(socket_, asio::buffer(*queue_.front()),
                    [self = shared_from_this()](boost::system::error_code ec, std::size_t n) {
                      self->bytesSent_ += n;
                      self->lastWritten_ = Clock::now();
                      if (ec || !self->open_) {
                        self->writing_ = false;
                        self->close();
                        return;
                      }
                      self->queue_.pop_front();
                      self->writeNext();
                    });
}

void Connection::startWatchdog(std::chrono::milliseconds idle, std::chrono::milliseconds writeStall) {
  idle_ = idle;
  writeStall_ = writeStall;
  lastReceived_ = Clock::now();
  asio::co_spawn(socket_.get_executor(), [self = shared_from_this()] { return self->watchdog(); }, asio::detached);
}

asio::awaitable<void> Connection::watchdog() {
  asio::steady_timer timer(socket_.get_executor());
  while (open_) {
    auto step = std::clamp(idle_ / 8, std::chrono::milliseconds(10), std::chrono::milliseconds(100));
    timer.expires_after(step);
    co_await timer.async_wait(asio::use_awaitable);
    auto now = Clock::now();
    bool quiet = idle_.count() > 0 && now - lastReceived_ > idle_;
    bool stalled = writing_ && writeStall_.count() > 0 && now - lastWritten_ > writeStall_;
    if (open_ && (quiet || stalled)) {
      timedOut_ = true;
      close();
    }
  }
}

}  // namespace tsr::cluster
