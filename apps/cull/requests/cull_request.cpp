#include "requests/cull_request.hpp"

#include <cmath>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "tsr/sg/coordinate_limit.hpp"

namespace tsr::app {

namespace {

using nlohmann::json;

glm::vec3 point(const json& j, const char* name) {
  if (!j.is_array() || j.size() != 3) throw CullRequestError(std::string(name) + ": expected [x, y, z]");
  glm::vec3 p;
  for (int i = 0; i < 3; ++i) {
    if (!j[i].is_number()) throw CullRequestError(std::string(name) + ": expected three numbers");
    const double v = j[i].get<double>();
    if (!std::isfinite(v) || !sg::withinCoordinateLimit(float(v)))
      throw CullRequestError(std::string(name) + ": coordinate beyond 1e12 or not finite");
    p[i] = float(v);
  }
  return p;
}

std::uint32_t count(const json& j, const char* name, std::uint32_t lo, std::uint32_t hi) {
  if (!j.is_number_integer() || j.get<std::int64_t>() < lo || j.get<std::int64_t>() > hi)
    throw CullRequestError(std::string(name) + ": expected an integer from " + std::to_string(lo) + " to " +
                           std::to_string(hi));
  return std::uint32_t(j.get<std::int64_t>());
}

}  // namespace

CullQuery parseCullRequest(const std::string& body, std::uint32_t maxObjects) {
  const json j = json::parse(body, nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw CullRequestError("the body is not a JSON object");
  for (const auto& [key, value] : j.items())
    if (key != "camera" && key != "width" && key != "height" && key != "max_objects")
      throw CullRequestError("unknown field '" + key + "' (fields: camera, width, height, max_objects)");
  if (!j.contains("camera") || !j["camera"].is_object()) throw CullRequestError("camera: expected an object");
  const json& c = j["camera"];
  for (const auto& [key, value] : c.items())
    if (key != "position" && key != "target" && key != "up" && key != "fov")
      throw CullRequestError("camera: unknown field '" + key + "' (fields: position, target, up, fov)");
  CullQuery q;
  if (!c.contains("position") || !c.contains("target")) throw CullRequestError("camera: needs position and target");
  q.position = point(c["position"], "camera.position");
  q.target = point(c["target"], "camera.target");
  if (c.contains("up")) q.up = point(c["up"], "camera.up");
  if (c.contains("fov")) {
    if (!c["fov"].is_number()) throw CullRequestError("camera.fov: expected degrees");
    const double fov = c["fov"].get<double>();
    if (!(fov > 0.5 && fov < 179.5)) throw CullRequestError("camera.fov: expected degrees between 0.5 and 179.5");
    q.fovDegrees = float(fov);
  }
  const glm::vec3 forward = q.target - q.position;
  if (!(glm::length(forward) > 0.0f)) throw CullRequestError("camera: position and target coincide");
  if (!(glm::length(glm::cross(forward, q.up)) > 1e-6f * glm::length(forward) * glm::length(q.up)))
    throw CullRequestError("camera.up: parallel to the view direction (or zero)");
  if (!j.contains("width") || !j.contains("height")) throw CullRequestError("width and height are required");
  q.width = count(j["width"], "width", 1, kMaxCullSide);
  q.height = count(j["height"], "height", 1, kMaxCullSide);
  q.maxObjects = j.contains("max_objects") ? count(j["max_objects"], "max_objects", 1, maxObjects) : maxObjects;
  return q;
}

std::string cullAnswerJson(const CullAnswer& answer) {
  json objects = json::array();
  for (const auto& o : answer.objects)
    objects.push_back(
        {{"id", o.id}, {"name", o.name}, {"pixels", o.pixels}, {"fraction", o.fraction}, {"triangles", o.triangles}});
  return json{{"objects", objects},
              {"covered_fraction", answer.coveredFraction},
              {"total_objects", answer.totalObjects},
              {"total_triangles", answer.totalTriangles}}
      .dump();
}

}  // namespace tsr::app
