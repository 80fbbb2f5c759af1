#include "requests/cull_view.hpp"

#include <glm/trigonometric.hpp>

#include "requests/cull_request.hpp"
#include "tsr/sg/camera.hpp"

namespace tsr::app {

med::View cullView(const CullQuery& q, float nearPlane, float farPlane) {
  sg::Camera camera;
  camera.setNearPlane(nearPlane);
  camera.setFarPlane(farPlane);
  camera.setVerticalFov(glm::radians(q.fovDegrees));
  camera.lookAt(q.position, q.target, q.up);
  med::View view = med::View::fromCamera(camera, q.width, q.height);
  try {
    view.validate();
  } catch (const std::invalid_argument& e) {
    throw CullRequestError(std::string("camera: no renderer can take this view (") + e.what() + ")");
  }
  return view;
}

}  // namespace tsr::app
