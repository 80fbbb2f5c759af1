#include "preview/preview_stream.hpp"

#include <condition_variable>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <spdlog/spdlog.h>
#include <boost/asio/post.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

#include "requests/cull_request.hpp"
#include "requests/preview_request.hpp"
#include "tsr/med/image_file.hpp"

namespace tsr::app {

namespace {

namespace beast = boost::beast;
namespace websocket = beast::websocket;
using nlohmann::json;

void putU32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(std::uint8_t(v >> (8 * i)));
}

// One browser's stream: its reads and writes run on the connection's
// strand (only the newest unsent frame is kept: a slow client skips
// frames, it never queues them); a render thread of its own refines the
// current view, cancelled mid-pass when a new message arrives. Both hold
// the client alive; it ends when the socket closes and the thread sees it.
class PreviewClient : public std::enable_shared_from_this<PreviewClient> {
 public:
  PreviewClient(beast::tcp_stream stream, const CullService& cull, const PreviewOptions& options,
                std::atomic<int>* counted, ClientSlot connection, ClientSlot preview)
      : ws_(std::move(stream)),
        cull_(cull),
        options_(options),
        counted_(counted),
        slots_{std::move(connection), std::move(preview)} {}
  ~PreviewClient() {
    if (counted_) --*counted_;
  }

  void start(HttpRequest upgrade) {
    // The WebSocket keeps its own deadlines: none on the TCP stream below it.
    beast::get_lowest_layer(ws_).expires_never();
    websocket::stream_base::timeout timeout;
    timeout.handshake_timeout = std::chrono::duration_cast<std::chrono::milliseconds>(options_.handshakeTimeout);
    timeout.idle_timeout = std::chrono::duration_cast<std::chrono::milliseconds>(options_.pingTimeout);
    timeout.keep_alive_pings = true;  // a ping at half the idle time; no answer by its end closes
    ws_.set_option(timeout);
    ws_.read_message_max(PreviewOptions::kMaxMessageBytes);
    upgrade_ = std::move(upgrade);
    ws_.async_accept(upgrade_, [self = shared_from_this()](beast::error_code ec) {
      if (ec) return;
      if (!self->counted_) {  // over the limit: open, say why, close
        self->ws_.async_close({websocket::close_code::try_again_later, "busy: too many previews at once"},
                              [self](beast::error_code) {});
        return;
      }
      std::thread([self] { self->renderLoop(); }).detach();
      self->read();
    });
  }

 private:
  void read() {
    ws_.async_read(in_, [self = shared_from_this()](beast::error_code ec, std::size_t) { self->onRead(ec); });
  }

  void onRead(beast::error_code ec) {
    if (ec) {
      std::lock_guard lock(mutex_);
      closed_ = true;
      cancel_ = true;
      wake_.notify_all();
      return;
    }
    const std::string text = beast::buffers_to_string(in_.data());
    in_.consume(in_.size());
    try {
      PreviewRequest request = parsePreviewRequest(text);
      std::lock_guard lock(mutex_);
      next_ = request;
      cancel_ = true;
      wake_.notify_all();
    } catch (const CullRequestError& e) {
      queue(json{{"error", std::string("bad message: ") + e.what()}}.dump(), false);
    }
    read();
  }

  // On the strand: the frame replaces one not yet sent.
  void queue(std::vector<std::uint8_t> message, bool binary) {
    pending_ = std::move(message);
    pendingBinary_ = binary;
    if (!writing_) write();
  }
  void queue(const std::string& text, bool binary) {
    queue(std::vector<std::uint8_t>(text.begin(), text.end()), binary);
  }

  // From the render thread.
  void send(std::vector<std::uint8_t> message, bool binary) {
    boost::asio::post(ws_.get_executor(), [self = shared_from_this(), message = std::move(message), binary]() mutable {
      self->queue(std::move(message), binary);
    });
  }

  void write() {
    if (!pending_) return;
    writing_ = true;
    out_ = std::move(*pending_);
    pending_.reset();
    ws_.binary(pendingBinary_);
    ws_.async_write(boost::asio::buffer(out_), [self = shared_from_this()](beast::error_code ec, std::size_t) {
      self->writing_ = false;
      if (!ec) self->write();
    });
  }

  void renderLoop() {
    std::unique_ptr<med::Viewport> viewport;
    for (;;) {
      PreviewRequest request;
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [this] { return closed_ || next_; });
        if (closed_) return;
        request = *next_;
        next_.reset();
        cancel_ = false;
      }
      if (!request.view) continue;  // stop: wait for the next view
      try {
        if (!viewport) viewport = options_.open();
        refine(*viewport, request.seq, *request.view);
      } catch (const std::exception& e) {
        spdlog::warn("preview failed: {}", e.what());
        const std::string text = json{{"seq", request.seq}, {"error", e.what()}}.dump();
        send({text.begin(), text.end()}, false);
      }
    }
  }

  // Samples 1, 2, 4, ... up to the limit, a frame after each step, until
  // the client says something new.
  void refine(med::Viewport& viewport, std::uint32_t seq, const CullQuery& query) {
    checkPreviewSize(query, options_.maxPixels);
    const med::View view = cull_.viewOf(query);
    med::FrameBuffer frame;
    med::RenderControl control;
    control.cancel = &cancel_;
    control.outputs = std::vector<std::string>{};
    std::uint32_t samples = 0;
    for (std::uint32_t want = 1; samples < options_.sampleLimit && !cancel_;
         want = std::min(want * 2, options_.sampleLimit)) {
      viewport.setParameter("spp", std::int64_t(want));
      const med::RenderStats stats = viewport.render(cull_.replica(), view, frame, control);
      if (cancel_) return;  // a new view came in mid-pass: this image is of the old one
      samples = stats.samples ? stats.samples : want;
      std::vector<std::uint8_t> message;
      putU32(message, seq);
      putU32(message, samples);
      putU32(message, frame.width);
      putU32(message, frame.height);
      const auto png = med::encodePng(frame);
      message.insert(message.end(), png.begin(), png.end());
      send(std::move(message), true);
    }
  }

  websocket::stream<beast::tcp_stream> ws_;
  const CullService& cull_;
  const PreviewOptions& options_;
  std::atomic<int>* counted_;  // the service's stream count, or none when refused
  ClientSlot slots_[2];
  HttpRequest upgrade_;
  beast::flat_buffer in_;
  std::optional<std::vector<std::uint8_t>> pending_;
  bool pendingBinary_ = true, writing_ = false;
  std::vector<std::uint8_t> out_;

  std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<PreviewRequest> next_;
  bool closed_ = false;
  std::atomic<bool> cancel_{false};
};

}  // namespace

void PreviewStreams::serve(beast::tcp_stream stream, HttpRequest upgrade, ClientSlot connection, ClientSlot preview) {
  std::atomic<int>* counted = &streams_;
  if (streams_.fetch_add(1) >= options_.maxStreams) {
    --streams_;
    counted = nullptr;
  }
  std::make_shared<PreviewClient>(std::move(stream), cull_, options_, counted, std::move(connection),
                                  std::move(preview))
      ->start(std::move(upgrade));
}

}  // namespace tsr::app
