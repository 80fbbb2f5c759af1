#include "protocol/connection.hpp"

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
  received(header.size());
  FrameHeader h = decodeFrameHeader(header);
  const MessageSpec& s = spec(h.type);
  if (s.sender != peer_) throw ProtocolError(Kind::Unexpected, std::string(s.name) + " may not be sent by this side");
  if (!authenticated_ && !s.beforeAuth)
    throw ProtocolError(Kind::Unexpected, std::string(s.name) + " before the handshake finished");
  Message m;
  m.type = h.type;
  // Grow with the bytes that actually arrive, so a large announced length
  // costs nothing until the peer sends that much; every read that returns
  // is a sign of life, however little it brought.
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  std::size_t have = 0;
  while (have < h.length) {
    if (m.payload.size() == have) m.payload.resize(have + std::min<std::size_t>(h.length - have, kChunk));
    std::size_t n = co_await socket_.async_read_some(asio::buffer(m.payload.data() + have, m.payload.size() - have),
                                                     asio::use_awaitable);
    have += n;
    received(n);
    if (onProgress_ && have < h.length && Clock::now() - lastProgress_ >= progressInterval_) {
      lastProgress_ = Clock::now();
      onProgress_();
    }
  }
  co_return m;
}

void Connection::received(std::size_t bytes) {
  lastReceived_ = Clock::now();
  bytesReceived_ += bytes;
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
  asio::post(socket_.get_executor(),
             [self = shared_from_this(), f = std::move(frame)]() mutable { self->send(std::move(f)); });
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
  written_ = 0;
}

void Connection::writeNext() {
  writing_ = true;
  if (queue_.empty()) {
    writing_ = false;
    if (closeAfterFlush_) close();
    return;
  }
  // In pieces, so the stall clock sees a slow peer's progress on one large frame.
  constexpr std::size_t kPiece = std::size_t{64} << 10;
  const auto& front = *queue_.front();
  std::size_t piece = std::min(kPiece, front.size() - written_);
  asio::async_write(socket_, asio::buffer(front.data() + written_, piece),
                    [self = shared_from_this()](boost::system::error_code ec, std::size_t n) {
                      self->bytesSent_ += n;
                      self->lastWritten_ = Clock::now();
                      if (ec || !self->open_) {
                        self->writing_ = false;
                        self->close();
                        return;
                      }
                      self->written_ += n;
                      if (self->written_ >= self->queue_.front()->size()) {
                        self->written_ = 0;
                        self->queue_.pop_front();
                      }
                      self->writeNext();
                    });
}

void Connection::startWatchdog(std::chrono::milliseconds idle, std::chrono::milliseconds writeStall) {
  idle_ = idle;
  writeStall_ = writeStall;
  lastReceived_ = Clock::now();
  asio::co_spawn(
      socket_.get_executor(), [self = shared_from_this()] { return self->watchdog(); }, asio::detached);
}

asio::awaitable<void> Connection::watchdog() {
  asio::steady_timer timer(socket_.get_executor());
  while (open_) {
    auto step = std::clamp(idle_ / 8, std::chrono::milliseconds(10), std::chrono::milliseconds(100));
    timer.expires_after(step);
    co_await timer.async_wait(asio::use_awaitable);
    auto now = Clock::now();
    bool quiet = idle_.count() > 0 && now - lastReceived_ > idle_;
    // A write that makes no progress is a stall only while the peer is silent
    // too: a large kernel buffer wakes a writer late (after it drained by half),
    // and a peer still talking to us is alive.
    bool stalled = writing_ && writeStall_.count() > 0 && now - std::max(lastWritten_, lastReceived_) > writeStall_;
    if (open_ && (quiet || stalled)) {
      timedOut_ = true;
      close();
    }
  }
}

}  // namespace tsr::cluster
