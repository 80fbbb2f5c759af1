#pragma once
// tessera-cull's HTTP side (Boost.Beast, asynchronous): POST /v1/cull, GET
// /v1/objects/{id}.glb, /v1/scene, /v1/status, the /v1/preview WebSocket
// and the web client's files. Every connection runs on a strand of a small
// fixed pool of threads, each read and write under a deadline
// (ServiceLimits); rankings wait in a bounded queue for their own worker,
// previews render on their own threads. With a token, /v1/ asks for it
// ("Authorization: Bearer TOKEN", or "?access_token=TOKEN" where a browser
// cannot set headers: WebSockets); the page's own files do not.
#include <atomic>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>

#include "preview/preview_stream.hpp"
#include "requests/access_token.hpp"
#include "requests/http_routes.hpp"
#include "requests/web_files.hpp"
#include "service/client_table.hpp"
#include "service/cull_queue.hpp"
#include "service/cull_service.hpp"
#include "service_limits.hpp"

namespace tsr::app {

struct HttpOptions {
  std::string token;               // empty: none asked (loopback only)
  std::uint32_t maxObjects = 256;  // the most a request may ask for, and the default
  ServiceLimits limits;
};

class HttpService : private ServedScene {
 public:
  HttpService(CullService& cull, PreviewStreams& previews, const WebFiles& web, HttpOptions options);
  // Accepts connections on `acceptor` (its io_context) and runs the
  // network's threads until the process ends.
  void serve(boost::asio::ip::tcp::acceptor& acceptor);

 private:
  class Session;
  void accept(boost::asio::ip::tcp::acceptor& acceptor);
  void pauseAccepting(boost::asio::ip::tcp::acceptor& acceptor, const boost::system::error_code& ec);
  void admit(boost::asio::ip::tcp::socket socket);

  std::string sceneJson() const override;
  std::optional<std::vector<std::uint8_t>> objectGlb(sg::ContainerId id) const override;
  std::string statusJson() const override;
  bool previews() const override { return previews_.enabled(); }
  med::View viewOf(const CullQuery& query) const override { return cull_.viewOf(query); }

  CullService& cull_;
  PreviewStreams& previews_;
  const HttpOptions options_;
  const AccessToken token_;
  const HttpRoutes routes_;
  ClientTable clients_;
  CullQueue queue_;
  std::atomic<int> refusing_{0};  // connections being refused (answered, then closed)
  std::atomic<std::uint64_t> refusedConnections_{0}, refusedRequests_{0}, refusedPreviews_{0}, timedOut_{0};
  std::atomic<std::int64_t> lastAcceptWarning_{std::numeric_limits<std::int64_t>::min() / 2};  // steady ticks
};

}  // namespace tsr::app
