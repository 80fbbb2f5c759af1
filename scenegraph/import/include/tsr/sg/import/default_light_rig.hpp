#pragma once
// The lights a scene gets when it brings none, as glTF viewers and
// usdview do (its "default dome light" and "camera light"): a neutral grey
// dome (the background, radiance kDomeRadiance in every direction) and a
// directional light shining along the camera's view (irradiance
// kCameraLightIrradiance), so what the camera sees is lit from the front.
// Both are ordinary scene containers, so every back-end, node and replica
// renders the same rig with the same meaning. A white Lambertian surface
// facing the camera, unoccluded, shows radiance 0.25 + 2 / pi ≈ 0.89.
#include "tsr/sg/types.hpp"

namespace tsr::sg {

class Scene;

inline constexpr float kDomeRadiance = 0.25f;
inline constexpr float kCameraLightIrradiance = 2.0f;

// True when the scene brings its own light: a Light container, geometry
// below `root` whose material emits, or a background that is not black.
bool hasOwnLighting(const Scene& scene, ContainerId root, ContainerId background);

struct DefaultLightRig {
  ContainerId dome = kNoContainer;      // the Background
  ContainerId follower = kNoContainer;  // Transform under root, at the camera
  ContainerId light = kNoContainer;     // directional, child of follower
  bool active() const { return light != kNoContainer; }
};

// Adds the rig: `background` (created when none is given) becomes the dome,
// a Transform holding the camera light is appended to the children of
// `root` (a Group or Transform). Logs that the default rig is in use.
DefaultLightRig addDefaultLightRig(Scene& scene, ContainerId root, ContainerId background);

// Puts the camera light where the camera is (its world pose); call it
// before each commit whose camera may have moved. Nothing for an inactive rig.
void followCamera(Scene& scene, const DefaultLightRig& rig, const Mat4& cameraWorld);

}  // namespace tsr::sg
