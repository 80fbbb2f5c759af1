#include "tsr/med/view_translation.hpp"

namespace tsr::med {

backend::Camera cameraOf(const View& view) {
  return backend::Camera{.cameraToWorld = view.cameraToWorld,
                         .left = view.left,
                         .right = view.right,
                         .bottom = view.bottom,
                         .top = view.top,
                         .near = view.nearPlane,
                         .far = view.farPlane,
                         .apertureRadius = view.apertureRadius,
                         .focusDistance = view.focusDistance,
                         .shutterOpen = view.shutterOpen,
                         .shutterClose = view.shutterClose,
                         .cameraToWorldAtEnd = view.cameraToWorldAtEnd};
}

backend::Region regionOf(const View& view) {
  return backend::Region{view.width, view.height, view.region.x0, view.region.y0, view.region.x1, view.region.y1};
}

}  // namespace tsr::med
