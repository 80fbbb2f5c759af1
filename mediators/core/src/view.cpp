#include "tsr/med/view.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "tsr/sg/coordinate_limit.hpp"
#include "tsr/sg/node_world.hpp"
#include "tsr/sg/shutter.hpp"

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
  // A shutter the camera cannot have is an instant at the frame's time.
  if (sg::shutterWithinFrame(camera.shutterOpen(), camera.shutterClose())) {
    v.shutterOpen = camera.shutterOpen();
    v.shutterClose = camera.shutterClose();
  }
  if (const glm::mat4 end = sg::cameraWorldPose(camera, sg::FrameTime::End); end != v.cameraToWorld)
    v.cameraToWorldAtEnd = end;
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
  const glm::mat4 shift = glm::translate(glm::mat4(1.0f), glm::vec3(offset, 0.0f, 0.0f));
  v.cameraToWorld = cameraToWorld * shift;
  if (cameraToWorldAtEnd) v.cameraToWorldAtEnd = *cameraToWorldAtEnd * shift;
  // Points on the zero-parallax plane project to the same pixel for both eyes.
  const float window = offset * nearPlane / zeroParallaxDistance;
  v.left -= window;
  v.right -= window;
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
  auto pose = [&](const glm::mat4& m, const std::string& what) {
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        if (!sg::withinCoordinateLimit(m[c][r]))
          fail(what + " entry " + number(m[c][r]) + " is not finite or beyond the coordinate limit of " +
               number(sg::kMaxCoordinate) + (c == 3 ? " (the eye position)" : ""));
  };
  pose(cameraToWorld, "camera pose");
  if (cameraToWorldAtEnd) pose(*cameraToWorldAtEnd, "camera pose at the frame's end");
  if (!sg::shutterWithinFrame(shutterOpen, shutterClose))
    fail("shutter " + number(shutterOpen) + "," + number(shutterClose) +
         " must open and close within the frame interval (0 <= open <= close <= 1)");
  if (!(apertureRadius >= 0.0f) || !sg::withinCoordinateLimit(apertureRadius))
    fail("aperture radius " + number(apertureRadius) + " must be finite and not negative");
  if (!(focusDistance > 0.0f) || !sg::withinCoordinateLimit(focusDistance))
    fail("focus distance " + number(focusDistance) + " must be finite and positive");
  for (float v : {left, right, bottom, top, nearPlane})
    if (!sg::withinCoordinateLimit(v))
      fail("frustum value " + number(v) + " is beyond the coordinate limit of " + number(sg::kMaxCoordinate));
}

}  // namespace tsr::med
