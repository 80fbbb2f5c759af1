#include <unistd.h>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <boost/beast/http.hpp>

#include "fuzz_targets.hpp"
#include "requests/cull_request.hpp"
#include "requests/cull_view.hpp"
#include "requests/http_routes.hpp"
#include "requests/preview_request.hpp"
#include "service_limits.hpp"

namespace tsr::fuzz {

namespace {

namespace http = boost::beast::http;

constexpr std::uint32_t kMaxObjects = 64;
constexpr float kNear = 0.1f, kFar = 1000.0f;  // a small scene's camera planes

// A scene of two objects as the routes see it (the ranking itself renders
// with the coverage back-end, which the fuzz build leaves out).
class SmallScene : public app::ServedScene {
 public:
  std::string sceneJson() const override { return R"({"total_objects":2,"total_triangles":3,"preview":true})"; }
  std::optional<std::vector<std::uint8_t>> objectGlb(sg::ContainerId id) const override {
    if (id != 3 && id != 7) return std::nullopt;
    return std::vector<std::uint8_t>{'g', 'l', 'T', 'F', 2, 0, 0, 0, 12, 0, 0, 0};
  }
  std::string statusJson() const override { return R"({"cull":{"waiting":0}})"; }
  bool previews() const override { return true; }
  med::View viewOf(const app::CullQuery& query) const override { return app::cullView(query, kNear, kFar); }
};

// The web client's folder: a page and one module.
std::filesystem::path webFolder() {
  auto root = std::filesystem::temp_directory_path() / ("tsr-fuzz-web-" + std::to_string(::getpid()));
  std::filesystem::create_directories(root / "src");
  std::ofstream(root / "index.html") << "<!doctype html><title>t</title>";
  std::ofstream(root / "src" / "main.js") << "export {};";
  return root;
}

void check(bool ok) {
  if (!ok) std::abort();
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

// One request's bytes as a connection delivers them: parsed with the
// service's limits, routed (token, path, method, view), and the reply
// written out and read back as HTTP. A cull's query must be one the
// ranking can take; a reply must be a well-formed response.
void cullHttpRequest(Bytes bytes) {
  static const SmallScene scene;
  static const app::WebFiles web(webFolder());
  static const app::AccessToken token("fuzz-token");
  static const app::HttpRoutes routes(scene, web, token, kMaxObjects);

  http::request_parser<http::string_body> parser;
  app::limitRequest(parser, app::ServiceLimits::kMaxHeaderBytes, app::ServiceLimits::kMaxBodyBytes);
  parser.eager(true);
  boost::beast::error_code ec;
  std::size_t used = 0;
  while (used < bytes.size() && !parser.is_done()) {
    const std::size_t n = parser.put(boost::asio::buffer(bytes.data() + used, bytes.size() - used), ec);
    if (ec == http::error::need_more) break;
    if (ec) return;  // refused: the service answers 400
    if (n == 0) break;
    used += n;
  }
  if (!parser.is_done()) {
    parser.put_eof(ec);
    if (ec || !parser.is_done()) return;
  }
  const app::HttpRequest request = parser.release();
  const app::Route route = routes.route(request);
  app::HttpResponse reply = route.reply;
  switch (route.kind) {
    case app::Route::Kind::Cull: {
      const app::CullQuery& q = route.query;
      check(routes.authorised(request));
      check(q.width >= 1 && q.width <= app::kMaxCullSide && q.height >= 1 && q.height <= app::kMaxCullSide);
      check(q.maxObjects >= 1 && q.maxObjects <= kMaxObjects);
      check(finite(q.position) && finite(q.target) && finite(q.up) && q.position != q.target);
      check(q.fovDegrees > 0.5f && q.fovDegrees < 179.5f);
      app::cullView(q, kNear, kFar).validate();  // the routes checked it: it must not throw
      reply = app::httpReply(request.version(), http::status::ok, app::cullAnswerJson({}), "application/json");
      break;
    }
    case app::Route::Kind::Preview:
      check(routes.authorised(request));
      return;  // the WebSocket's messages have a target of their own
    case app::Route::Kind::Reply:
      // 500 is what the routes answer to an exception nobody meant: a finding.
      check(reply.result_int() >= 200 && reply.result_int() < 600 && reply.result_int() != 500);
      break;
  }
  std::ostringstream out;
  out << reply;
  const std::string text = out.str();
  http::response_parser<http::string_body> back;
  back.body_limit(16u << 20);
  back.eager(true);
  back.put(boost::asio::buffer(text), ec);
  if (!ec && !back.is_done()) back.put_eof(ec);
  check(!ec && back.is_done() && back.get().result_int() == reply.result_int());
}

// One text message of a /v1/preview stream, as the service reads it.
void cullPreviewMessage(Bytes bytes) {
  const std::string text(bytes.begin(), bytes.end());
  app::PreviewRequest request;
  try {
    request = app::parsePreviewRequest(text);
  } catch (const app::CullRequestError&) {
    return;
  }
  if (!request.view) return;
  const app::CullQuery& q = *request.view;
  check(q.maxObjects == 1 && q.width >= 1 && q.width <= app::kMaxCullSide && q.height >= 1 &&
        q.height <= app::kMaxCullSide);
  check(finite(q.position) && finite(q.target) && q.position != q.target);
  try {
    app::checkPreviewSize(q, 1024 * 1024);
  } catch (const app::CullRequestError&) {
    check(std::uint64_t(q.width) * q.height > 1024 * 1024);
  }
  // As the stream's renderer takes it: a view, or a refusal naming why.
  try {
    app::cullView(q, kNear, kFar).validate();
  } catch (const app::CullRequestError&) {}
}

}  // namespace tsr::fuzz
