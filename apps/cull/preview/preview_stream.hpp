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
// The socket is served on the network's threads (the connection's strand);
// each stream renders on a thread of its own. A stream that answers no
// ping for `pingTimeout` is closed.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>

#include <boost/beast/core/tcp_stream.hpp>

#include "requests/http_routes.hpp"
#include "service/client_table.hpp"
#include "service/cull_service.hpp"
#include "tsr/med/viewport.hpp"

namespace tsr::app {

struct PreviewOptions {
  // A viewport of the preview's back-end (here, over the service's one
  // conversion, or on a cluster's nodes); nullptr: no previews.
  std::function<std::unique_ptr<med::Viewport>()> open;
  int maxStreams = 4;                     // more are refused with "busy"
  std::uint32_t sampleLimit = 64;         // per pixel, then the image stands
  std::uint64_t maxPixels = 1024 * 1024;  // per frame
  std::chrono::duration<double> handshakeTimeout{5.0}, pingTimeout{20.0};
  static constexpr std::size_t kMaxMessageBytes = 4096;
};

class PreviewStreams {
 public:
  PreviewStreams(const CullService& cull, PreviewOptions options) : cull_(cull), options_(std::move(options)) {}
  bool enabled() const { return bool(options_.open); }
  int active() const { return streams_.load(); }
  int limit() const { return options_.maxStreams; }
  // Takes over the connection whose request asked for the upgrade and
  // streams until the client leaves, holding the client's slots (its
  // connection, its stream) as long. Over the limit the WebSocket opens
  // and closes at once: "busy".
  void serve(boost::beast::tcp_stream stream, HttpRequest upgrade, ClientSlot connection, ClientSlot preview);

 private:
  const CullService& cull_;
  PreviewOptions options_;
  std::atomic<int> streams_{0};
};

}  // namespace tsr::app
