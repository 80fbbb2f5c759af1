#pragma once
// The camera a program looks through: the scene's own (chosen by name or
// index), one framing the scene's bounds when it has none, or one placed by
// the user (look-from, look-at, field of view). Every program that shows a
// scene (tessera-render, the viewer, the wall) starts from these, so the
// same scene opens on the same view everywhere.
#include <optional>
#include <string>
#include <vector>

#include "tsr/sg/types.hpp"

namespace tsr::sg {

class Scene;

// A camera at the root of the scene that sees the bounds of `root` from the
// front (+Z), the bounding sphere inside its 45° vertical field of view.
ContainerId addFramingCamera(Scene& scene, ContainerId root);

// `choice` is a camera's name (exactly) or its index in `cameras` (as the
// import listed them). Throws std::invalid_argument naming the choices
// when it matches none, or when a name matches several.
ContainerId chooseCamera(const Scene& scene, const std::vector<ContainerId>& cameras, const std::string& choice);

// A user's placement of the view. Unset parts keep the base camera's:
// look-from alone looks at the centre of the bounds, look-at alone looks
// from where the base camera is; fovDegrees alone changes the field of
// view, and the lens or shutter settings alone those.
struct LookOverride {
  std::optional<Vec3> from, at;
  std::optional<float> fovDegrees;      // vertical, 0 < fov < 180
  std::optional<float> apertureRadius;  // scene units, >= 0 (0: a pinhole)
  // Or the lens as a photographer states it: radius = focal length / (2 N),
  // the focal length that of a full-frame camera (a 24 mm tall sensor) with
  // this field of view, in metres (glTF's unit). > 0; not with apertureRadius.
  std::optional<float> fNumber;
  std::optional<float> focusDistance;  // scene units along the view, > 0
  std::optional<Vec2> shutter;         // open, close: fractions of the frame interval, 0 <= open <= close <= 1
  bool any() const { return from || at || fovDegrees || apertureRadius || fNumber || focusDistance || shutter; }
};

// Throws std::invalid_argument (a message naming the option: --look-from,
// --look-at, --fov, --aperture, --f-number, --focus-distance, --shutter) for non-finite or
// out-of-range values, or from == at.
void validate(const LookOverride& look);

// The camera to look through once `look` is applied to `base`: with a
// look-from or look-at, a new camera at the root of the scene (fixed in the
// world; field of view and stereo settings from `base`, near and far planes
// holding the bounds of `root`); with only a field of view, lens or
// shutter, `base` itself with those (still moved by its parents).
// An f-number becomes a radius in scene units of `metresPerUnit` metres
// (ImportResult::metresPerUnit). Validates first.
ContainerId applyLookOverride(Scene& scene, ContainerId root, ContainerId base, const LookOverride& look,
                              float metresPerUnit);

// The aperture radius in metres of f-number `n` for a vertical field of view
// (radians): a full-frame camera's focal length, 0.012 m / tan(fov / 2), over 2n.
float apertureOfFNumber(float n, float verticalFov);

}  // namespace tsr::sg
