#include "requests/http_routes.hpp"

#include <charconv>

#include <spdlog/spdlog.h>
#include <boost/beast/websocket/rfc6455.hpp>

#include "requests/cull_request.hpp"

namespace tsr::app {

namespace {

namespace http = boost::beast::http;

std::string_view view(boost::beast::string_view s) { return {s.data(), s.size()}; }

// The target without its query string.
std::string_view pathOf(boost::beast::string_view target) { return view(target).substr(0, view(target).find('?')); }

// The value of `name` in the target's query string, as sent (tokens are
// plain characters: no decoding needed).
std::optional<std::string_view> queryValue(boost::beast::string_view whole, std::string_view name) {
  const std::string_view target = view(whole);
  const auto start = target.find('?');
  if (start == std::string_view::npos) return std::nullopt;
  std::string_view query = target.substr(start + 1);
  while (!query.empty()) {
    const std::string_view pair = query.substr(0, query.find('&'));
    if (pair.size() > name.size() && pair.starts_with(name) && pair[name.size()] == '=')
      return pair.substr(name.size() + 1);
    query.remove_prefix(std::min(query.size(), pair.size() + 1));
  }
  return std::nullopt;
}

// "/v1/objects/123.glb" -> 123; nothing for any other path (no dots, no
// slashes, no leading zeros or signs: one way to name an object).
std::optional<sg::ContainerId> objectPath(std::string_view target) {
  constexpr std::string_view prefix = "/v1/objects/", suffix = ".glb";
  if (!target.starts_with(prefix) || !target.ends_with(suffix) || target.size() < prefix.size() + suffix.size())
    return std::nullopt;
  const std::string_view digits = target.substr(prefix.size(), target.size() - prefix.size() - suffix.size());
  if (digits.empty() || digits.size() > 15 || (digits.size() > 1 && digits[0] == '0')) return std::nullopt;
  sg::ContainerId id = 0;
  auto [end, err] = std::from_chars(digits.data(), digits.data() + digits.size(), id);
  if (err != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
  return id;
}

}  // namespace

HttpResponse httpReply(unsigned version, http::status status, std::string body, const char* type) {
  HttpResponse r{status, version};
  r.set(http::field::server, "tessera-cull");
  r.set(http::field::content_type, type);
  r.body() = std::move(body);
  r.prepare_payload();
  return r;
}

HttpResponse httpRefusal(unsigned version, http::status status, std::string why, int retryAfterSeconds) {
  HttpResponse r = httpReply(version, status, std::move(why) + "\n");
  r.set(http::field::retry_after, std::to_string(retryAfterSeconds));
  r.keep_alive(false);
  return r;
}

bool HttpRoutes::authorised(const HttpRequest& request) const {
  if (!token_.required()) return true;
  constexpr std::string_view bearer = "Bearer ";
  const std::string_view header = view(request[http::field::authorization]);
  if (header.starts_with(bearer) && token_.accepts(header.substr(bearer.size()))) return true;
  const auto query = queryValue(request.target(), "access_token");
  return query && token_.accepts(*query);
}

Route HttpRoutes::route(const HttpRequest& request) const {
  Route route;
  route.reply = respond(request, route);
  return route;
}

HttpResponse HttpRoutes::respond(const HttpRequest& request, Route& route) const {
  const unsigned v = request.version();
  const std::string_view target = pathOf(request.target());
  if (target.starts_with("/v1/") && !authorised(request))
    return httpReply(v, http::status::unauthorized,
                     "unauthorized: send Authorization: Bearer TOKEN (or ?access_token=TOKEN)\n");
  try {
    if (target == "/v1/preview") {
      if (!scene_.previews()) return httpReply(v, http::status::not_found, "this service streams no previews\n");
      if (!boost::beast::websocket::is_upgrade(request))
        return httpReply(v, http::status::upgrade_required, "/v1/preview is a WebSocket\n");
      route.kind = Route::Kind::Preview;
      return {};
    }
    if (target == "/v1/scene" || target == "/v1/status") {
      if (request.method() != http::verb::get) return httpReply(v, http::status::method_not_allowed, "use GET\n");
      HttpResponse r = httpReply(v, http::status::ok, target == "/v1/scene" ? scene_.sceneJson() : scene_.statusJson(),
                                 "application/json");
      if (target == "/v1/status") r.set(http::field::cache_control, "no-store");
      return r;
    }
    if (target == "/v1/cull") {
      if (request.method() != http::verb::post) return httpReply(v, http::status::method_not_allowed, "use POST\n");
      route.query = parseCullRequest(request.body(), maxObjects_);
      scene_.viewOf(route.query);  // refused here (400), not in the queue (500)
      route.kind = Route::Kind::Cull;
      return {};
    }
    if (target.starts_with("/v1/objects/")) {
      if (request.method() != http::verb::get) return httpReply(v, http::status::method_not_allowed, "use GET\n");
      const auto id = objectPath(target);
      if (!id) return httpReply(v, http::status::bad_request, "expected /v1/objects/ID.glb with a decimal ID\n");
      // Objects never change while the service runs: the id is the version.
      const std::string etag = "\"" + std::to_string(*id) + "\"";
      if (view(request[http::field::if_none_match]) == etag) {
        HttpResponse r = httpReply(v, http::status::not_modified, "");
        r.set(http::field::etag, etag);
        return r;
      }
      auto glb = scene_.objectGlb(*id);
      if (!glb) return httpReply(v, http::status::not_found, "no object " + std::to_string(*id) + "\n");
      HttpResponse r = httpReply(v, http::status::ok, std::string(glb->begin(), glb->end()), "model/gltf-binary");
      r.set(http::field::etag, etag);
      r.set(http::field::cache_control, "public, max-age=86400");
      return r;
    }
    if (request.method() == http::verb::get) {
      if (auto file = web_.get(target)) {
        HttpResponse r = httpReply(v, http::status::ok, std::move(file->body), file->contentType.c_str());
        r.set(http::field::cache_control, "no-cache");  // revalidated: the page follows the installed client
        return r;
      }
    }
    return httpReply(v, http::status::not_found,
                     "not found: / (the web client), /v1/cull (POST), /v1/objects/ID.glb, /v1/scene, /v1/status, "
                     "/v1/preview\n");
  } catch (const WebPathError& e) {
    return httpReply(v, http::status::bad_request, std::string("bad path: ") + e.what() + "\n");
  } catch (const CullRequestError& e) {
    return httpReply(v, http::status::bad_request, std::string("bad request: ") + e.what() + "\n");
  } catch (const std::exception& e) {
    spdlog::error("{} failed: {}", std::string(target), e.what());
    return httpReply(v, http::status::internal_server_error, std::string("failed: ") + e.what() + "\n");
  }
}

}  // namespace tsr::app
