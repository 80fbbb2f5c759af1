#include "service/cull_service.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "backends.hpp"
#include "requests/cull_view.hpp"
#include "scene/scene_glb.hpp"
#include "tsr/med/coverage/ranking.hpp"
#include "tsr/med/scene_flattening.hpp"
#include "tsr/sg/import/scene_stats.hpp"
#include "tsr/sg/node_world.hpp"

namespace tsr::app {

CullService::CullService(const std::string& scene, const sg::ImportOptions& import, const std::string& backend,
                         const med::Parameters& parameters) {
  session_.load(scene, import);
  session_.publish();
  registerBackends(registry_);
  viewport_ = registry_.create(settingsFor(backend, parameters), contexts_);
  const auto offered = viewport_->outputNames();
  if (std::find(offered.begin(), offered.end(), med::kIdOutput) == offered.end())
    throw std::invalid_argument("--backend " + backend + " has no object ids to rank by (try coverage)");
  // Converted once, here, acceleration structures included (the back-end
  // builds them at its first render): the first request waits for nothing.
  viewport_->synchronize(session_.replica);
  med::FrameBuffer warmUp;
  med::RenderControl control;
  control.outputs = std::vector<std::string>{med::kIdOutput};
  const auto* camera = session_.replica.scene().find<sg::Camera>(session_.camera);
  viewport_->render(session_.replica, med::View::fromCamera(*camera, 8, 8), warmUp, control);
  const sg::Scene& s = session_.replica.scene();
  for (const med::FlatNode& instance : med::flatten(s, session_.imported.root).instances) {
    const auto* geometry = s.find<sg::Geometry>(instance.id);
    const std::uint64_t triangles = geometry ? geometry->triangleCount() : 0;
    const sg::ContainerId object = med::objectOf(s, instance);
    parts_[object].push_back(instance);
    triangles_[object] += triangles;
    totalTriangles_ += triangles;
  }
  if (const auto stats = sg::computeSceneStats(s, session_.imported.root); stats.hasBounds) {
    boundsMin_ = stats.boundsMin;
    boundsMax_ = stats.boundsMax;
  }
}

med::View CullService::viewOf(const CullQuery& q) const {
  const auto* sceneCamera = session_.replica.scene().find<sg::Camera>(session_.camera);
  return cullView(q, sceneCamera->nearPlane(), sceneCamera->farPlane());
}

CullAnswer CullService::cull(const CullQuery& q, const std::atomic<bool>* cancel) {
  const med::View view = viewOf(q);
  med::FrameBuffer image;
  med::RenderControl control;
  control.cancel = cancel;
  control.outputs = std::vector<std::string>{med::kIdOutput};
  {
    std::lock_guard lock(mutex_);
    viewport_->render(session_.replica, view, image, control);
  }
  const sg::Scene& scene = session_.replica.scene();
  const std::vector<med::RankedObject> ranked = med::rankObjects(image, scene);
  CullAnswer answer;
  const double all = double(q.width) * double(q.height);
  answer.coveredFraction = 1.0 - double(med::backgroundPixels(image)) / all;
  answer.totalObjects = triangles_.size();
  answer.totalTriangles = totalTriangles_;
  for (const auto& r : ranked) {
    if (answer.objects.size() >= q.maxObjects) break;
    auto t = triangles_.find(r.id);
    answer.objects.push_back({r.id, r.name, r.pixels, r.fraction, t == triangles_.end() ? 0 : t->second});
  }
  return answer;
}

med::ViewportSettings CullService::settingsFor(const std::string& backend, const med::Parameters& parameters) const {
  return {backend, session_.imported.root, session_.imported.background, registry_.parametersFor(backend, parameters),
          true};
}

CullQuery CullService::sceneView() const {
  const sg::Scene& s = session_.replica.scene();
  const auto* camera = s.find<sg::Camera>(session_.camera);
  const glm::mat4 pose = sg::cameraWorldPose(*camera);
  CullQuery q;
  q.position = glm::vec3(pose[3]);
  q.target = q.position - glm::vec3(pose[2]);  // it looks down its -Z
  q.up = glm::vec3(pose[1]);
  q.fovDegrees = glm::degrees(camera->verticalFov());
  return q;
}

// What the path tracer shows behind everything, for the page to match:
// a colour or a vertical gradient, scaled by the intensity (an environment
// image is left to the page's own backdrop).
nlohmann::json CullService::backgroundJson() const {
  const auto* bg = session_.replica.scene().find<sg::Background>(session_.imported.background);
  if (!bg) return {{"kind", "color"}, {"color", {0, 0, 0}}};
  const float k = bg->intensity();
  auto vec = [k](const glm::vec3& v) { return nlohmann::json::array({v.x * k, v.y * k, v.z * k}); };
  switch (bg->kind()) {
    case sg::BackgroundKind::Gradient:
      return {{"kind", "gradient"}, {"top", vec(bg->gradientTop())}, {"bottom", vec(bg->gradientBottom())}};
    case sg::BackgroundKind::Environment:
      return {{"kind", "environment"}};
    default:
      return {{"kind", "color"}, {"color", vec(bg->color())}};
  }
}

std::string CullService::sceneJson(bool preview) const {
  const CullQuery view = sceneView();
  auto vec = [](const glm::vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); };
  const auto* camera = session_.replica.scene().find<sg::Camera>(session_.camera);
  return nlohmann::json{{"camera",
                         {{"position", vec(view.position)},
                          {"target", vec(view.target)},
                          {"up", vec(view.up)},
                          {"fov", view.fovDegrees},
                          {"near", camera->nearPlane()},
                          {"far", camera->farPlane()}}},
                        {"bounds", {{"min", vec(boundsMin_)}, {"max", vec(boundsMax_)}}},
                        {"background", backgroundJson()},
                        {"total_objects", totalObjects()},
                        {"total_triangles", totalTriangles_},
                        {"preview", preview}}
      .dump();
}

std::optional<std::vector<std::uint8_t>> CullService::objectGlb(sg::ContainerId id) const {
  auto parts = parts_.find(id);
  if (parts == parts_.end()) return std::nullopt;
  return glbOf(session_.replica.scene(), parts->second);
}

}  // namespace tsr::app
