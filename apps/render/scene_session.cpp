#include "scene_session.hpp"

#include <cmath>

#include "tsr/sg/import/scene_stats.hpp"

namespace tsr::app {

void SceneSession::load(const std::string& scene, const sg::ImportOptions& options) {
  imported = sg::importScene(source, scene, options);
  if (!imported.cameras.empty()) {
    camera = imported.cameras.front();
    return;
  }
  // Frame the bounds from the front (+Z), the whole box inside a 45° view.
  auto stats = sg::computeSceneStats(source, imported.root);
  sg::Vec3 lo = stats.hasBounds ? stats.boundsMin : sg::Vec3(-1), hi = stats.hasBounds ? stats.boundsMax : sg::Vec3(1);
  sg::Vec3 centre = (lo + hi) * 0.5f;
  float radius = std::max(glm::length(hi - lo) * 0.5f, 1e-3f);
  auto& cam = source.create<sg::Camera>("default camera");
  float distance = radius / std::sin(cam.verticalFov() * 0.5f);
  cam.lookAt(centre + sg::Vec3(0, 0, distance), centre);
  cam.setNearPlane(distance * 1e-3f);
  cam.setFarPlane(distance + radius * 4);
  camera = cam.id();
}

sg::ChangeListPtr SceneSession::publish() {
  auto list = source.commit();
  replica.apply(list);
  return list;
}

}  // namespace tsr::app
