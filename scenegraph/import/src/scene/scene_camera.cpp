#include "tsr/sg/import/scene_camera.hpp"
#include "tsr/sg/shutter.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <glm/glm.hpp>

#include "tsr/sg/coordinate_limit.hpp"
#include "tsr/sg/import/scene_stats.hpp"
#include "tsr/sg/node_world.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::sg {
namespace {

struct Sphere {
  Vec3 centre{0.0f};
  float radius = 1.0f;
};

Sphere boundingSphere(const Scene& scene, ContainerId root) {
  const SceneStats stats = computeSceneStats(scene, root);
  const Vec3 lo = stats.hasBounds ? stats.boundsMin : Vec3(-1), hi = stats.hasBounds ? stats.boundsMax : Vec3(1);
  return {(lo + hi) * 0.5f, std::max(glm::length(hi - lo) * 0.5f, 1e-3f)};
}

// Near and far planes for an eye `distance` from the centre of a sphere.
void fitPlanes(Camera& camera, float distance, float radius) {
  const float far = distance + radius * 4;
  camera.setFarPlane(far);
  camera.setNearPlane(far * 1e-4f);
}

// Points the camera; an up vector along the view would make no frame.
void aim(Camera& camera, const Vec3& from, const Vec3& at) {
  const Vec3 forward = glm::normalize(at - from);
  const Vec3 up = std::abs(forward.y) > 0.999f ? Vec3(0, 0, -1) : Vec3(0, 1, 0);
  camera.lookAt(from, at, up);
}

std::string text(const Vec3& v) {
  std::ostringstream s;
  s << v.x << "," << v.y << "," << v.z;
  return s.str();
}

}  // namespace

ContainerId addFramingCamera(Scene& scene, ContainerId root) {
  const Sphere bounds = boundingSphere(scene, root);
  auto& camera = scene.create<Camera>("default camera");
  const float distance = bounds.radius / std::sin(camera.verticalFov() * 0.5f);
  aim(camera, bounds.centre + Vec3(0, 0, distance), bounds.centre);
  camera.setNearPlane(distance * 1e-3f);
  camera.setFarPlane(distance + bounds.radius * 4);
  return camera.id();
}

ContainerId chooseCamera(const Scene& scene, const std::vector<ContainerId>& cameras, const std::string& choice) {
  std::string list;
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    const Container* c = scene.find(cameras[i]);
    list += (i ? ", " : "") + std::to_string(i) + (c && !c->name().empty() ? " '" + c->name() + "'" : "");
  }
  const std::string offered = cameras.empty() ? " (the scene has no cameras)" : " (cameras: " + list + ")";
  ContainerId named = kNoContainer;
  for (ContainerId id : cameras) {
    const Container* c = scene.find(id);
    if (!c || c->name() != choice) continue;
    if (named != kNoContainer && named != id)
      throw std::invalid_argument("--camera " + choice + ": several cameras have that name; give its index" + offered);
    named = id;
  }
  if (named != kNoContainer) return named;
  std::size_t index = 0;
  std::istringstream in(choice);
  if (!choice.empty() && std::all_of(choice.begin(), choice.end(), [](char ch) { return ch >= '0' && ch <= '9'; }) &&
      (in >> index) && index < cameras.size())
    return cameras[index];
  throw std::invalid_argument("--camera " + choice + ": no camera has that name or index" + offered);
}

void validate(const LookOverride& look) {
  for (const auto& [name, v] : {std::pair{"--look-from", look.from}, std::pair{"--look-at", look.at}})
    if (v && !(withinCoordinateLimit(v->x) && withinCoordinateLimit(v->y) && withinCoordinateLimit(v->z)))
      throw std::invalid_argument(std::string(name) + " " + text(*v) + ": expected finite coordinates within ±" +
                                  std::to_string(kMaxCoordinate));
  if (look.from && look.at && glm::length(*look.at - *look.from) <= 1e-6f * std::max(1.0f, glm::length(*look.from)))
    throw std::invalid_argument("--look-from and --look-at are the same point (" + text(*look.from) +
                                "): the view has no direction");
  if (look.fovDegrees && !(*look.fovDegrees > 0.0f && *look.fovDegrees < 180.0f))
    throw std::invalid_argument("--fov " + std::to_string(*look.fovDegrees) +
                                ": expected a vertical field of view in degrees, 0 < fov < 180");
  if (look.apertureRadius && !(*look.apertureRadius >= 0.0f && withinCoordinateLimit(*look.apertureRadius)))
    throw std::invalid_argument("--aperture " + std::to_string(*look.apertureRadius) +
                                ": expected the lens' radius in scene units, 0 (a pinhole) or more");
  if (look.fNumber && !(*look.fNumber > 0.0f && withinCoordinateLimit(*look.fNumber)))
    throw std::invalid_argument("--f-number " + std::to_string(*look.fNumber) +
                                ": expected the lens' f-number above 0 (e.g. 2.8)");
  if (look.fNumber && look.apertureRadius)
    throw std::invalid_argument("--f-number and --aperture both set the lens: give one");
  if (look.shutter && !shutterWithinFrame(look.shutter->x, look.shutter->y))
    throw std::invalid_argument("--shutter " + std::to_string(look.shutter->x) + "," + std::to_string(look.shutter->y) +
                                ": expected OPEN,CLOSE as fractions of the frame interval, 0 <= OPEN <= CLOSE <= 1");
  if (look.focusDistance && !(*look.focusDistance > 0.0f && withinCoordinateLimit(*look.focusDistance)))
    throw std::invalid_argument("--focus-distance " + std::to_string(*look.focusDistance) +
                                ": expected a distance in scene units above 0");
}

ContainerId applyLookOverride(Scene& scene, ContainerId root, ContainerId base, const LookOverride& look,
                              float metresPerUnit) {
  validate(look);
  if (!(metresPerUnit > 0.0f && std::isfinite(metresPerUnit)))
    throw std::invalid_argument("a scene unit of " + std::to_string(metresPerUnit) + " m: expected a length above 0");
  auto* original = scene.find<Camera>(base);
  if (!original) throw std::invalid_argument("container " + std::to_string(base) + " is not a camera of the scene");
  const float fov = look.fovDegrees ? glm::radians(*look.fovDegrees) : original->verticalFov();
  const float aperture = look.fNumber ? apertureOfFNumber(*look.fNumber, fov) / metresPerUnit
                                      : look.apertureRadius.value_or(original->apertureRadius());
  const float focus = look.focusDistance.value_or(original->focusDistance());
  const Vec2 shutter = look.shutter.value_or(Vec2(original->shutterOpen(), original->shutterClose()));
  if (!look.from && !look.at) {
    original->setVerticalFov(fov);  // it stays where it is, under its parents
    original->setApertureRadius(aperture);
    original->setFocusDistance(focus);
    original->setShutterOpen(shutter.x);
    original->setShutterClose(shutter.y);
    return base;
  }
  const Mat4 basePose = cameraWorldPose(scene, base);
  const Sphere bounds = boundingSphere(scene, root);
  const Vec3 from = look.from.value_or(Vec3(basePose[3]));
  const Vec3 at = look.at.value_or(bounds.centre);
  if (glm::length(at - from) <= 1e-6f * std::max(1.0f, glm::length(from)))
    throw std::invalid_argument(std::string(look.from
                                                ? "--look-from " + text(from) + " is the centre of the scene's bounds"
                                                : "--look-at " + text(at) + " is where the camera stands") +
                                ": the view has no direction (give both --look-from and --look-at)");
  auto& camera = scene.create<Camera>("look camera");
  camera.setVerticalFov(fov);
  camera.setEyeSeparation(original->eyeSeparation());
  camera.setZeroParallaxDistance(original->zeroParallaxDistance());
  camera.setApertureRadius(aperture);
  camera.setFocusDistance(focus);
  camera.setShutterOpen(shutter.x);
  camera.setShutterClose(shutter.y);
  aim(camera, from, at);
  fitPlanes(camera, glm::length(from - bounds.centre), bounds.radius);
  return camera.id();
}

float apertureOfFNumber(float n, float verticalFov) {
  constexpr float kHalfSensorHeight = 0.012f;  // metres: a 36 x 24 mm sensor
  return kHalfSensorHeight / std::tan(0.5f * verticalFov) / (2.0f * n);
}

}  // namespace tsr::sg
