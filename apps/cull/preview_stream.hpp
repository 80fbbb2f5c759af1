#pragma once
// GET /v1/preview, upgraded to a WebSocket: the path tracer's progressive,
// filtered image of the browser's view, refined and streamed until the
// view changes (Schwenk figure 5.6's "rasterise while moving, trace at
// rest", the browser rasterising). The client sends text messages
//   {"seq": N, "view": {"camera": {...}, "width": W, "height": H}}
//   {"seq": N, "stop": true}
// (a view as POST /v1/cull takes it); the service answers each view with
// binary frames, better each time, until the sample limit or the next
// message: 16 bytes (little-endian uint32 seq, samples, width, height)
// then the image as PNG. Problems come as text {"seq": N, "error": "..."}.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/http.hpp>

#include "cull_service.hpp"
#include "tsr/med/viewport.hpp"

namespace tsr::app {

struct PreviewOptions {
  // A viewport of the preview's back-end (here, over the service's one
  // conversion, or on a cluster's nodes); nullptr: no previews.
  std::function<std::unique_ptr<med::Viewport>()> open;
  int maxStreams = 4;                     // more are refused with "busy"
  std::uint32_t sampleLimit = 64;         // per pixel, then the image stands
  std::uint64_t maxPixels = 1024 * 1024;  // per frame
  static constexpr std::size_t kMaxMessageBytes = 4096;
};

class PreviewStreams {
 public:
  PreviewStreams(const CullService& cull, PreviewOptions options) : cull_(cull), options_(std::move(options)) {}
  bool enabled() const { return bool(options_.open); }
  // Takes over the connection whose request asked for the upgrade and
  // streams until the client leaves.
  void serve(boost::asio::ip::tcp::socket socket,
             const boost::beast::http::request<boost::beast::http::string_body>& upgrade);

 private:
  const CullService& cull_;
  PreviewOptions options_;
  std::atomic<int> streams_{0};
};

}  // namespace tsr::app
