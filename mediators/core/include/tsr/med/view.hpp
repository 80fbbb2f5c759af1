#pragma once
// Where a viewport looks and which pixels it fills: a camera pose, an
// off-axis frustum window for the FULL image, the full image size, and the
// rectangle of it to render. A wall tile, a load-balanced tile or one eye
// is just another View; back-ends key their random numbers on full-image
// pixel coordinates, so a region renders exactly the crop of the full image.
#include <cstdint>
#include <optional>

#include <glm/mat4x4.hpp>

#include "tsr/sg/camera.hpp"

namespace tsr::med {

struct PixelRect {
  std::uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [x0, x1) x [y0, y1), row 0 at the top
  std::uint32_t width() const { return x1 - x0; }
  std::uint32_t height() const { return y1 - y0; }
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool operator==(const PixelRect&) const = default;
};

enum class Eye { Left, Right };

struct View {
  glm::mat4 cameraToWorld{1.0f};                     // camera looks down -Z, +Y up
  float left = -1, right = 1, bottom = -1, top = 1;  // window on the plane z = -near
  float nearPlane = 0.1f, farPlane = 1000.0f;
  // A thin lens in the eye's xy plane (0: a pinhole), focused on the plane
  // z = -focusDistance. Back-ends without depth of field
  // (BackendCapabilities::depthOfField false) render the pinhole.
  float apertureRadius = 0.0f, focusDistance = 5.0f;
  // The shutter, as fractions of the frame interval (equal: an instant),
  // and where the camera is at the interval's end when it moves over it.
  // Back-ends without motion blur (BackendCapabilities::motionBlur false)
  // render the scene at the frame's time.
  float shutterOpen = 0.0f, shutterClose = 0.0f;
  std::optional<glm::mat4> cameraToWorldAtEnd;
  std::uint32_t width = 0, height = 0;  // the full image
  PixelRect region;                     // the part to render

  // A symmetric frustum from a scene camera for a width x height image, at
  // the camera's world pose (the Transforms above it included), with its
  // lens and shutter.
  static View fromCamera(const sg::Camera& camera, std::uint32_t width, std::uint32_t height);
  // The same image, only the pixels of `rect` (a tile).
  View cropped(const PixelRect& rect) const;
  // One eye of a stereo pair: moved by half the separation along the camera's
  // x axis, with the window shifted so the zero-parallax plane stays put.
  View eye(Eye which, float separation, float zeroParallaxDistance) const;

  // Throws std::invalid_argument on an empty image or region, a region
  // outside the image, a degenerate frustum, or a pose or window with a
  // value beyond sg::kMaxCoordinate (the far plane may be larger), or a
  // shutter outside 0 <= open <= close <= 1.
  void validate() const;
  bool operator==(const View&) const = default;
};

}  // namespace tsr::med
