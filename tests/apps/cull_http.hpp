#pragma once
// Plain HTTP requests to a tessera-cull on 127.0.0.1, and the Cornell box
// views the culling-service tests ask for.
#include <cstdint>
#include <string>

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <glm/trigonometric.hpp>
#include <nlohmann/json.hpp>

#include "scene/scene_session.hpp"
#include "tsr/med/view.hpp"

namespace tsr::app::test {

struct Reply {
  unsigned status = 0;
  std::string body;
  std::string etag;
  std::string contentType;
};

inline Reply request(std::uint16_t port, boost::beast::http::verb verb, const std::string& target,
                     const std::string& body = {}, const std::string& ifNoneMatch = {},
                     const std::string& authorization = {}) {
  namespace http = boost::beast::http;
  boost::asio::io_context io;
  boost::asio::ip::tcp::socket socket(io);
  socket.connect({boost::asio::ip::make_address("127.0.0.1"), port});
  http::request<http::string_body> req{verb, target, 11};
  req.set(http::field::host, "127.0.0.1");
  if (!ifNoneMatch.empty()) req.set(http::field::if_none_match, ifNoneMatch);
  if (!authorization.empty()) req.set(http::field::authorization, authorization);
  req.body() = body;
  req.prepare_payload();
  http::write(socket, req);
  boost::beast::flat_buffer buffer;
  http::response_parser<http::string_body> parser;
  parser.body_limit(64 << 20);
  http::read(socket, buffer, parser);
  const auto& res = parser.get();
  return {res.result_int(), res.body(), std::string(res[http::field::etag]),
          std::string(res[http::field::content_type])};
}

// What tessera-cull makes of cornellView's camera: the pose and field of
// view asked for, with the near and far planes of the scene's camera.
inline med::View cornellServiceView(const SceneSession& session, std::uint32_t width, std::uint32_t height) {
  const auto* sceneCamera = session.replica.scene().find<sg::Camera>(session.camera);
  sg::Camera camera;
  camera.setNearPlane(sceneCamera->nearPlane());
  camera.setFarPlane(sceneCamera->farPlane());
  camera.setVerticalFov(glm::radians(39.0f));
  camera.lookAt({278, 273, -800}, {278, 273, 0});
  return med::View::fromCamera(camera, width, height);
}

// The Cornell box seen from in front, as the browser would ask.
inline nlohmann::json cornellView(int width, int height, int maxObjects, float x = 278.0f) {
  return {{"camera", {{"position", {x, 273, -800}}, {"target", {278, 273, 0}}, {"fov", 39}}},
          {"width", width},
          {"height", height},
          {"max_objects", maxObjects}};
}

}  // namespace tsr::app::test
