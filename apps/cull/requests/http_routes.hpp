#pragma once
// What tessera-cull makes of one HTTP request, apart from the network: the
// token checked, the path and method matched, the view decoded. Most
// requests are answered here; a cull is handed back as its checked query
// (the service queues it), a preview upgrade as such (the service streams
// it). The fuzz target feeds requests through here as the service does.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <boost/beast/http.hpp>

#include "cull_query.hpp"
#include "requests/access_token.hpp"
#include "requests/web_files.hpp"
#include "tsr/med/view.hpp"

namespace tsr::app {

using HttpRequest = boost::beast::http::request<boost::beast::http::string_body>;
using HttpResponse = boost::beast::http::response<boost::beast::http::string_body>;

HttpResponse httpReply(unsigned version, boost::beast::http::status status, std::string body,
                       const char* type = "text/plain");
// 429 or 503 with Retry-After, closing the connection: a limit's answer.
HttpResponse httpRefusal(unsigned version, boost::beast::http::status status, std::string why,
                         int retryAfterSeconds = 1);

// What the routes read of the service: its scene's description, its
// objects, how busy it is.
class ServedScene {
 public:
  virtual ~ServedScene() = default;
  virtual std::string sceneJson() const = 0;
  virtual std::optional<std::vector<std::uint8_t>> objectGlb(sg::ContainerId id) const = 0;
  virtual std::string statusJson() const = 0;
  virtual bool previews() const = 0;
  // The query as the ranking renders it (cull_view.hpp): CullRequestError
  // for one it could not.
  virtual med::View viewOf(const CullQuery& query) const = 0;
};

struct Route {
  enum class Kind { Reply, Cull, Preview };
  Kind kind = Kind::Reply;
  HttpResponse reply;  // Kind::Reply
  CullQuery query;     // Kind::Cull, checked
};

class HttpRoutes {
 public:
  HttpRoutes(const ServedScene& scene, const WebFiles& web, const AccessToken& token, std::uint32_t maxObjects)
      : scene_(scene), web_(web), token_(token), maxObjects_(maxObjects) {}
  // Never throws for any request: a mistake is a 4xx reply.
  Route route(const HttpRequest& request) const;
  bool authorised(const HttpRequest& request) const;

 private:
  HttpResponse respond(const HttpRequest& request, Route& route) const;

  const ServedScene& scene_;
  const WebFiles& web_;
  const AccessToken& token_;
  std::uint32_t maxObjects_;
};

// The service's limits on one request's header and body, set on a parser.
template <class Parser>
void limitRequest(Parser& parser, std::size_t headerBytes, std::size_t bodyBytes) {
  parser.header_limit(std::uint32_t(headerBytes));
  parser.body_limit(bodyBytes);
}

}  // namespace tsr::app
