#include "tsr/med/view.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "tsr/sg/coordinate_limit.hpp"
#include "tsr/sg/node_world.hpp"

namespace tsr::med {

View View::fromCamera(const sg::Camera& camera, std::uint32_t width, std::uint32_t height) {
  View v;
  v.cameraToWorld = sg::cameraWorldPose(camera);
  v.nearPlane = camera.nearPlane();
  v.farPlane = camera.farPlane();
  // A lens the camera cannot have (negative, NaN, no focus) is the pinhole.
  const bool lens = std::isfinite(camera.apertureRadius()) && camera.apertureRadius() > 0.0f &&
                    sg::withinCoordinateLimit(camera.apertureRadius()) && std::isfinite(camera.focusDistance()) &&
                    camera.focusDistance() > 0.0f && sg::withinCoordinateLimit(camera.focusDistance());
  if (lens) {
    v.apertureRadius = camera.apertureRadius();
    v.focusDistance = camera.focusDistance();
  }
  float halfHeight = v.nearPlane * std::tan(camera.verticalFov() * 0.5f);
  float aspect = height ? static_cast<float>(width) / static_cast<float>(height) : 1.0f;
  v.top = halfHeight;
  v.bottom = -halfHeight;
  v.right = halfHeight * aspect;
  v.left = -v.right;
  v.width = width;
  v.height = height;
  v.region = {0, 0, width, height};
  return v;
}

View View::cropped(const PixelRect& rect) const {
  View v = *this;
  v.region = rect;
  return v;
}

View View::eye(Eye which, float separation, float zeroParallaxDistance) const {
  if (!(zeroParallaxDistance > 0)) throw std::invalid_argument("zero-parallax distance must be positive");
  float offset = (which == Eye::Left ? -0.5f : 0.5f) * separation;
  View v = *this;
  v.cameraToWorld = cameraToWorld * glm::translate(glm::mat4(1.0f), glm::vec3(offset, 0.0f, 0.0f));
  // Points on the zero-parallax plane project to the same pixel for both eyes.
  float shift = offset * nearPlane / zeroParallaxDistance;
  v.left -= shift;
  v.right -= shift;
  return v;
}

void View::validate() const {
  auto fail = [](const std::string& why) { throw std::invalid_argument("view: " + why); };
  if (width == 0 || height == 0) fail("image size is 0");
  if (region.empty()) fail("empty region");
  if (region.x1 > width || region.y1 > height) fail("region outside the image");
  if (!(right > left) || !(top > bottom)) fail("empty frustum window");
  if (!(nearPlane > 0) || !(farPlane > nearPlane)) fail("near must be positive and below far");
  // A pose or window beyond sg::kMaxCoordinate gives rays no back-end can trace.
  auto number = [](float v) {
    std::ostringstream s;
    s << v;
    return s.str();
  };
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!sg::withinCoordinateLimit(cameraToWorld[c][r]))
        fail("camera pose entry " + number(cameraToWorld[c][r]) + " is not finite or beyond the coordinate limit of " +
             number(sg::kMaxCoordinate) + (c == 3 ? " (the eye position)" : ""));
  if (!(apertureRadius >= 0.0f) || !sg::withinCoordinateLimit(apertureRadius))
    fail("aperture radius " + number(apertureRadius) + " must be finite and not negative");
  if (!(focusDistance > 0.0f) || !sg::withinCoordinateLimit(focusDistance))
    fail("focus distance " + number(focusDistance) + " must be finite and positive");
  for (float v : {left, right, bottom, top, nearPlane})
    if (!sg::withinCoordinateLimit(v))
      fail("frustum value " + number(v) + " is beyond the coordinate limit of " + number(sg::kMaxCoordinate));
}

}  // namespace tsr::med
