#include "cull_service.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "backends.hpp"
#include "scene_glb.hpp"
#include "tsr/med/coverage/ranking.hpp"
#include "tsr/med/scene_flattening.hpp"

namespace tsr::app {

CullService::CullService(const std::string& scene, const sg::ImportOptions& import, const std::string& backend,
                         const med::Parameters& parameters) {
  session_.load(scene, import);
  session_.publish();
  registerBackends(registry_);
  med::ViewportSettings settings{backend, session_.imported.root, session_.imported.background,
                                 registry_.parametersFor(backend, parameters), true};
  viewport_ = registry_.create(settings, contexts_);
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
}

CullAnswer CullService::cull(const CullQuery& q) {
  // A camera of the query's pose and field of view, with the near and far
  // planes of the scene's own camera (they fit its scale).
  const auto* sceneCamera = session_.replica.scene().find<sg::Camera>(session_.camera);
  sg::Camera camera;
  camera.setNearPlane(sceneCamera->nearPlane());
  camera.setFarPlane(sceneCamera->farPlane());
  camera.setVerticalFov(glm::radians(q.fovDegrees));
  camera.lookAt(q.position, q.target, q.up);
  med::View view = med::View::fromCamera(camera, q.width, q.height);
  view.validate();

  med::FrameBuffer image;
  med::RenderControl control;
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

std::optional<std::vector<std::uint8_t>> CullService::objectGlb(sg::ContainerId id) const {
  auto parts = parts_.find(id);
  if (parts == parts_.end()) return std::nullopt;
  return glbOf(session_.replica.scene(), parts->second);
}

}  // namespace tsr::app
