#pragma once
// tessera-cull's HTTP side (Boost.Beast): POST /v1/cull, GET
// /v1/objects/{id}.glb, GET /v1/scene, the /v1/preview WebSocket and the
// web client's files; one thread per connection (at most kMaxConnections),
// requests bounded in header and body, every refusal a 4xx with a one-line
// message, and the service serving on regardless. With a token, /v1/ asks
// for it ("Authorization: Bearer TOKEN", or "?access_token=TOKEN" where a
// browser cannot set headers: WebSockets); the page's own files do not.
#include <atomic>
#include <cstdint>
#include <string>

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/http.hpp>

#include "cull_service.hpp"
#include "preview_stream.hpp"
#include "web_files.hpp"

namespace tsr::app {

struct HttpOptions {
  std::string token;               // empty: none asked (loopback only)
  std::uint32_t maxObjects = 256;  // the most a request may ask for, and the default
};

class HttpService {
 public:
  static constexpr int kMaxConnections = 64;
  static constexpr std::size_t kMaxBodyBytes = 64 * 1024;
  static constexpr std::size_t kMaxHeaderBytes = 8 * 1024;

  HttpService(CullService& cull, PreviewStreams& previews, const WebFiles& web, HttpOptions options)
      : cull_(cull), previews_(previews), web_(web), options_(std::move(options)) {}
  // Accepts connections on `acceptor` until the process ends.
  void serve(boost::asio::ip::tcp::acceptor& acceptor);

 private:
  void session(boost::asio::ip::tcp::socket socket);
  boost::beast::http::response<boost::beast::http::string_body> handle(
      const boost::beast::http::request<boost::beast::http::string_body>& request);
  bool authorised(const boost::beast::http::request<boost::beast::http::string_body>& request) const;

  CullService& cull_;
  PreviewStreams& previews_;
  const WebFiles& web_;
  HttpOptions options_;
  std::atomic<int> connections_{0};
};

}  // namespace tsr::app
