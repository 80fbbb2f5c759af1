#include "tsr/sg/node_world.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/matrix.hpp>

#include "tsr/sg/scene.hpp"

namespace tsr::sg {

Mat4 parentWorldMatrix(const Scene& scene, ContainerId node, FrameTime when) {
  Mat4 world(1.0f);
  // The graph is acyclic (the scene refuses cycles), so this walk ends.
  for (ContainerId child = node;;) {
    ContainerId parent = kNoContainer;
    for (ContainerId id : scene.referrers(child)) {
      const Container* c = scene.find(id);
      if (c && isParentType(c->type()) && (parent == kNoContainer || id < parent)) parent = id;
    }
    if (parent == kNoContainer) return world;
    if (const auto* t = scene.find<Transform>(parent))
      world = (when == FrameTime::End ? t->matrixAtEnd() : t->matrix()) * world;
    child = parent;
  }
}

Mat4 cameraWorldPose(const Scene& scene, ContainerId camera, FrameTime when) {
  const auto* c = scene.find<Camera>(camera);
  if (!c) throw std::invalid_argument("container " + std::to_string(camera) + " is not a camera of the scene");
  return parentWorldMatrix(scene, camera, when) * c->pose();
}

Mat4 cameraWorldPose(const Camera& camera, FrameTime when) {
  return camera.scene() ? parentWorldMatrix(*camera.scene(), camera.id(), when) * camera.pose() : camera.pose();
}

void setCameraWorldPose(Camera& camera, const Mat4& world) {
  const Mat4 parent = camera.scene() ? parentWorldMatrix(*camera.scene(), camera.id()) : Mat4(1.0f);
  // A parent scaled to nothing (an animation passing through scale 0) has no
  // inverse: the camera keeps its pose rather than taking NaNs.
  if (!(std::abs(glm::determinant(parent)) > 1e-12f)) return;
  camera.setPose(glm::inverse(parent) * world);
}

}  // namespace tsr::sg
