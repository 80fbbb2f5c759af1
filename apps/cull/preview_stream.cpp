#include "preview_stream.hpp"

#include <unistd.h>

#include <condition_variable>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <spdlog/spdlog.h>
#include <boost/asio/io_context.hpp>
#include <boost/asio/post.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

#include "cull_request.hpp"
#include "tsr/med/image_file.hpp"

namespace tsr::app {

namespace {

namespace beast = boost::beast;
namespace websocket = beast::websocket;
using boost::asio::ip::tcp;
using nlohmann::json;

struct PreviewRequest {
  std::uint32_t seq = 0;
  std::optional<CullQuery> view;  // none: stop refining
};

PreviewRequest parsePreviewRequest(const std::string& text) {
  const json j = json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw CullRequestError("the message is not a JSON object");
  for (const auto& [key, value] : j.items())
    if (key != "seq" && key != "view" && key != "stop")
      throw CullRequestError("unknown field '" + key + "' (fields: seq, view, stop)");
  PreviewRequest r;
  if (!j.contains("seq") || !j["seq"].is_number_unsigned() || j["seq"].get<std::uint64_t>() > 0xffffffffu)
    throw CullRequestError("seq: expected an integer from 0 to 4294967295");
  r.seq = j["seq"].get<std::uint32_t>();
  if (j.contains("view") == j.contains("stop")) throw CullRequestError("expected either view or stop");
  if (j.contains("view")) {
    if (!j["view"].is_object()) throw CullRequestError("view: expected an object");
    r.view = parseCullRequest(j["view"].dump(), 1);
  }
  return r;
}

void putU32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(std::uint8_t(v >> (8 * i)));
}

// One browser's stream: an Asio loop of its own reads the client's
// messages and writes frames (only the newest unsent one is kept: a slow
// client skips frames, it never queues them); a render thread refines the
// current view, cancelled mid-pass when a new message arrives.
class PreviewClient {
 public:
  PreviewClient(tcp::socket& accepted, const CullService& cull, const PreviewOptions& options)
      : ws_(adopt(io_, accepted)), cull_(cull), options_(options) {}

  void run(const beast::http::request<beast::http::string_body>& upgrade) {
    ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws_.read_message_max(PreviewOptions::kMaxMessageBytes);
    ws_.accept(upgrade);
    std::thread renderer([this] { renderLoop(); });
    read();
    io_.run();
    {
      std::lock_guard lock(mutex_);
      closed_ = true;
      cancel_ = true;
    }
    wake_.notify_all();
    renderer.join();
  }

  // The connection moves onto this client's own loop (the acceptor's loop
  // runs nowhere: the HTTP side is synchronous).
  static tcp::socket adopt(boost::asio::io_context& io, tcp::socket& socket) {
    tcp::socket own(io);
    own.assign(socket.local_endpoint().protocol(), ::dup(socket.native_handle()));
    socket.close();
    return own;
  }

 private:
  void read() {
    ws_.async_read(in_, [this](beast::error_code ec, std::size_t) {
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
        next_ = std::move(request);
        cancel_ = true;
        wake_.notify_all();
      } catch (const CullRequestError& e) {
        sendText(json{{"error", std::string("bad message: ") + e.what()}}.dump());
      }
      read();
    });
  }

  // From any thread: the frame replaces one not yet sent.
  void send(std::vector<std::uint8_t> message, bool binary) {
    boost::asio::post(io_, [this, message = std::move(message), binary]() mutable {
      pending_ = std::move(message);
      pendingBinary_ = binary;
      if (!writing_) write();
    });
  }
  void sendText(const std::string& text) { send({text.begin(), text.end()}, false); }

  void write() {
    if (!pending_) return;
    writing_ = true;
    out_ = std::move(*pending_);
    pending_.reset();
    ws_.binary(pendingBinary_);
    ws_.async_write(boost::asio::buffer(out_), [this](beast::error_code ec, std::size_t) {
      writing_ = false;
      if (!ec) write();
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
        request = std::move(*next_);
        next_.reset();
        cancel_ = false;
      }
      if (!request.view) continue;  // stop: wait for the next view
      try {
        if (!viewport) viewport = options_.open();
        refine(*viewport, request.seq, *request.view);
      } catch (const std::exception& e) {
        spdlog::warn("preview failed: {}", e.what());
        sendText(json{{"seq", request.seq}, {"error", e.what()}}.dump());
      }
    }
  }

  // Samples 1, 2, 4, ... up to the limit, a frame after each step, until
  // the client says something new.
  void refine(med::Viewport& viewport, std::uint32_t seq, const CullQuery& query) {
    if (std::uint64_t(query.width) * query.height > options_.maxPixels)
      throw CullRequestError("view of " + std::to_string(query.width) + "x" + std::to_string(query.height) +
                             " pixels: previews take at most " + std::to_string(options_.maxPixels));
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

  boost::asio::io_context io_;
  websocket::stream<tcp::socket> ws_;
  const CullService& cull_;
  const PreviewOptions& options_;
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

void PreviewStreams::serve(tcp::socket socket, const beast::http::request<beast::http::string_body>& upgrade) {
  if (streams_.fetch_add(1) >= options_.maxStreams) {
    --streams_;
    websocket::stream<tcp::socket> ws(std::move(socket));
    beast::error_code ec;
    ws.accept(upgrade, ec);
    if (!ec) ws.close({websocket::close_code::try_again_later, "busy: too many previews at once"}, ec);
    return;
  }
  try {
    auto client = std::make_unique<PreviewClient>(socket, cull_, options_);
    client->run(upgrade);
  } catch (const std::exception& e) {
    spdlog::warn("preview stream ended: {}", e.what());
  }
  --streams_;
}

}  // namespace tsr::app
