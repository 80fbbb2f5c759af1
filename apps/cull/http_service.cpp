#include "http_service.hpp"

#include <sys/socket.h>

#include <charconv>
#include <thread>

#include <spdlog/spdlog.h>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include "cull_request.hpp"

namespace tsr::app {

namespace {

namespace http = boost::beast::http;
using Response = http::response<http::string_body>;

Response reply(unsigned version, http::status status, std::string body, const char* type = "text/plain") {
  Response r{status, version};
  r.set(http::field::server, "tessera-cull");
  r.set(http::field::content_type, type);
  r.body() = std::move(body);
  r.prepare_payload();
  return r;
}

// "/v1/objects/123.glb" -> 123; nothing for any other path (no dots, no
// slashes, no leading zeros or signs: one way to name an object).
std::string_view view(boost::beast::string_view s) { return {s.data(), s.size()}; }

// The target without its query string.
std::string_view pathOf(boost::beast::string_view target) { return view(target).substr(0, view(target).find('?')); }

// The value of `name` in the target's query string, as sent (tokens are
// plain characters: no decoding needed).
std::string_view queryValue(boost::beast::string_view whole, std::string_view name) {
  const std::string_view target = view(whole);
  const auto start = target.find('?');
  if (start == std::string_view::npos) return {};
  std::string_view query = target.substr(start + 1);
  while (!query.empty()) {
    const std::string_view pair = query.substr(0, query.find('&'));
    if (pair.size() > name.size() && pair.starts_with(name) && pair[name.size()] == '=')
      return pair.substr(name.size() + 1);
    query.remove_prefix(std::min(query.size(), pair.size() + 1));
  }
  return {};
}

std::optional<sg::ContainerId> objectPath(std::string_view target) {
  constexpr std::string_view prefix = "/v1/objects/", suffix = ".glb";
  if (!target.starts_with(prefix) || !target.ends_with(suffix)) return std::nullopt;
  const std::string_view digits = target.substr(prefix.size(), target.size() - prefix.size() - suffix.size());
  if (digits.empty() || digits.size() > 15 || (digits.size() > 1 && digits[0] == '0')) return std::nullopt;
  sg::ContainerId id = 0;
  auto [end, err] = std::from_chars(digits.data(), digits.data() + digits.size(), id);
  if (err != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
  return id;
}

}  // namespace

void HttpService::serve(boost::asio::ip::tcp::acceptor& acceptor) {
  for (;;) {
    boost::asio::ip::tcp::socket socket(acceptor.get_executor());
    boost::system::error_code ec;
    acceptor.accept(socket, ec);
    if (ec) continue;
    if (connections_.load() >= kMaxConnections) {
      socket.close(ec);  // over the limit: refused at once, the others go on
      continue;
    }
    ++connections_;
    std::thread([this, s = std::move(socket)]() mutable {
      session(std::move(s));
      --connections_;
    }).detach();
  }
}

void HttpService::session(boost::asio::ip::tcp::socket socket) {
  // A client that goes quiet for 30 s loses its connection (and thread).
  timeval timeout{30, 0};
  setsockopt(socket.native_handle(), SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  boost::beast::flat_buffer buffer;
  for (;;) {
    http::request_parser<http::string_body> parser;
    parser.header_limit(kMaxHeaderBytes);
    parser.body_limit(kMaxBodyBytes);
    boost::system::error_code ec;
    http::read(socket, buffer, parser, ec);
    if (ec == http::error::end_of_stream || ec == boost::asio::error::connection_reset) return;
    Response response;
    bool keepAlive = false;
    if (ec) {
      response = reply(11, http::status::bad_request, "bad request: " + ec.message() + "\n");
    } else {
      const auto& request = parser.get();
      if (boost::beast::websocket::is_upgrade(request) && pathOf(request.target()) == "/v1/preview" &&
          previews_.enabled() && authorised(request)) {
        socket.set_option(boost::asio::socket_base::keep_alive(true));
        previews_.serve(std::move(socket), request);  // the connection is the stream's now
        return;
      }
      keepAlive = request.keep_alive();
      response = handle(request);
      response.keep_alive(keepAlive);
    }
    http::write(socket, response, ec);
    if (ec || !keepAlive) return;
  }
}

bool HttpService::authorised(const http::request<http::string_body>& request) const {
  return options_.token.empty() || request[http::field::authorization] == "Bearer " + options_.token ||
         queryValue(request.target(), "access_token") == options_.token;
}

Response HttpService::handle(const http::request<http::string_body>& request) {
  const unsigned v = request.version();
  const std::string_view target = pathOf(request.target());
  if (target.starts_with("/v1/") && !authorised(request))
    return reply(v, http::status::unauthorized,
                 "unauthorized: send Authorization: Bearer TOKEN (or ?access_token=TOKEN)\n");
  try {
    if (target == "/v1/preview")
      return reply(v, previews_.enabled() ? http::status::upgrade_required : http::status::not_found,
                   previews_.enabled() ? "/v1/preview is a WebSocket\n" : "this service streams no previews\n");
    if (target == "/v1/scene") {
      if (request.method() != http::verb::get) return reply(v, http::status::method_not_allowed, "use GET\n");
      return reply(v, http::status::ok, cull_.sceneJson(previews_.enabled()), "application/json");
    }
    if (target == "/v1/cull") {
      if (request.method() != http::verb::post) return reply(v, http::status::method_not_allowed, "use POST\n");
      const CullQuery query = parseCullRequest(request.body(), options_.maxObjects);
      return reply(v, http::status::ok, cullAnswerJson(cull_.cull(query)), "application/json");
    }
    if (target.starts_with("/v1/objects/")) {
      if (request.method() != http::verb::get) return reply(v, http::status::method_not_allowed, "use GET\n");
      const auto id = objectPath(target);
      if (!id) return reply(v, http::status::bad_request, "expected /v1/objects/ID.glb with a decimal ID\n");
      // Objects never change while the service runs: the id is the version.
      const std::string etag = "\"" + std::to_string(*id) + "\"";
      if (request[http::field::if_none_match] == etag) {
        Response r = reply(v, http::status::not_modified, "");
        r.set(http::field::etag, etag);
        return r;
      }
      auto glb = cull_.objectGlb(*id);
      if (!glb) return reply(v, http::status::not_found, "no object " + std::to_string(*id) + "\n");
      Response r = reply(v, http::status::ok, std::string(glb->begin(), glb->end()), "model/gltf-binary");
      r.set(http::field::etag, etag);
      r.set(http::field::cache_control, "public, max-age=86400");
      return r;
    }
    if (request.method() == http::verb::get) {
      if (auto file = web_.get(target)) {
        Response r = reply(v, http::status::ok, std::move(file->body), file->contentType.c_str());
        r.set(http::field::cache_control, "no-cache");  // revalidated: the page follows the installed client
        return r;
      }
    }
    return reply(v, http::status::not_found,
                 "not found: / (the web client), /v1/cull (POST), /v1/objects/ID.glb, /v1/scene, /v1/preview\n");
  } catch (const WebPathError& e) {
    return reply(v, http::status::bad_request, std::string("bad path: ") + e.what() + "\n");
  } catch (const CullRequestError& e) {
    return reply(v, http::status::bad_request, std::string("bad request: ") + e.what() + "\n");
  } catch (const std::exception& e) {
    spdlog::error("{} failed: {}", std::string(target), e.what());
    return reply(v, http::status::internal_server_error, std::string("failed: ") + e.what() + "\n");
  }
}

}  // namespace tsr::app
