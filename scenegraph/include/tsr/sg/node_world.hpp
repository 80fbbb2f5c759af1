#pragma once
// Where a node sits in the world: the product of the Transforms above it.
// Cameras are nodes too, so an animated parent moves the camera under it.
#include "tsr/sg/types.hpp"

namespace tsr::sg {

class Scene;
class Camera;

// Which instant of the frame interval a world matrix is for: the frame's
// time, or the interval's end (Transform::frameMotion() applied).
enum class FrameTime : bool { Now, End };

// The product of the Transform matrices from a root down to `node`
// (excluded). A node held by several parents (instanced) follows, at each
// level, the parent with the smallest id; a node without parents, or not in
// the scene, has the identity.
Mat4 parentWorldMatrix(const Scene& scene, ContainerId node, FrameTime when = FrameTime::Now);

// A camera's pose in the world: parentWorldMatrix * Camera::pose().
// Throws std::invalid_argument when `camera` is not a Camera of the scene.
Mat4 cameraWorldPose(const Scene& scene, ContainerId camera, FrameTime when = FrameTime::Now);
// The same for a camera held by a scene (its pose, for one held by none).
Mat4 cameraWorldPose(const Camera& camera, FrameTime when = FrameTime::Now);
// Sets the camera's pose so that its world pose becomes `world`: the
// transforms above it undone, so navigation in world space moves a camera
// that hangs under a node (every glTF camera) where it is asked to. Under a
// transform that has no inverse (scale 0) the pose is left as it was.
void setCameraWorldPose(Camera& camera, const Mat4& world);

}  // namespace tsr::sg
