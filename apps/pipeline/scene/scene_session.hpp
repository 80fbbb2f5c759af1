#pragma once
// The application side of a render: the authoring scene loaded from a file
// or a built-in, the camera to look through, the default light rig when the
// scene brings no light, and a replica fed by commits (the render thread's
// copy, in the DESIGN's words).
#include <cstdint>
#include <optional>
#include <string>

#include "tsr/sg/import/default_light_rig.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/import/scene_camera.hpp"
#include "tsr/sg/replica.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::app {

// --focus-on X,Y: the lens focuses on what pixel (x, y) of a width x height
// image sees.
struct FocusOn {
  std::uint32_t x = 0, y = 0, width = 1, height = 1;
};

// How the user asked to look at the scene (--camera, --look-*, --fov,
// --aperture, --focus-distance, --focus-on, --no-default-light).
struct ViewChoice {
  std::string camera;  // name or index; empty: the scene's first camera
  sg::LookOverride look;
  std::optional<FocusOn> focusOn;
  bool defaultLight = true;
};

struct SceneSession {
  sg::Scene source;
  sg::ImportResult imported;
  sg::ContainerId camera = sg::kNoContainer;
  sg::DefaultLightRig rig;  // active only when added
  sg::Replica replica;

  // Imports `scene`; picks the camera (adds one framing the bounds when the
  // scene has none), applies the look override, and adds the default light
  // rig to a scene without lights; with focusOn, sets the camera's focus
  // distance to the depth that pixel sees (a one-pixel path-traced render).
  // Throws sg::ImportError or std::invalid_argument.
  void load(const std::string& scene, const sg::ImportOptions& options = {}, const ViewChoice& view = {});
  // Poses every animation at `seconds`, with its motion over the next
  // `frameInterval` seconds when the camera's shutter stays open over part
  // of the frame (Transform::frameMotion, which the shutter blurs; a
  // shutter that is an instant leaves the motion unedited).
  void poseAnimations(double seconds, double frameInterval);
  // Whether the camera's shutter stays open over part of the frame.
  bool shutterStaysOpen() const;
  // Moves the rig's camera light to the camera and commits the frame's edits.
  sg::ChangeListPtr commit();
  // commit(), and the list applied to the replica.
  sg::ChangeListPtr publish();
};

}  // namespace tsr::app
