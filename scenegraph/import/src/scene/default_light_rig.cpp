#include "tsr/sg/import/default_light_rig.hpp"

#include <stdexcept>
#include <string>

#include <spdlog/spdlog.h>

#include "tsr/sg/import/scene_stats.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::sg {
namespace {

bool black(const Vec3& c) { return !(c.x > 0.0f || c.y > 0.0f || c.z > 0.0f); }

bool backgroundLights(const Scene& scene, ContainerId id) {
  const auto* bg = scene.find<Background>(id);
  if (!bg || !(bg->intensity() > 0.0f)) return false;
  switch (bg->kind()) {
    case BackgroundKind::Gradient:
      return !black(bg->gradientTop()) || !black(bg->gradientBottom());
    case BackgroundKind::Environment:
      return scene.find<Image>(bg->environment()) != nullptr || !black(bg->color());
    default:
      return !black(bg->color());
  }
}

}  // namespace

bool hasOwnLighting(const Scene& scene, ContainerId root, ContainerId background) {
  if (scene.count(ContainerType::Light) > 0 || backgroundLights(scene, background)) return true;
  // Bounds are not needed: a vertex limit of 0 keeps the walk cheap.
  return computeSceneStats(scene, root, 0).emissiveGeometries > 0;
}

DefaultLightRig addDefaultLightRig(Scene& scene, ContainerId root, ContainerId background) {
  Container* parent = scene.find(root);
  if (!parent || !isParentType(parent->type()))
    throw std::invalid_argument("default light rig: container " + std::to_string(root) +
                                " is not a group or transform");
  DefaultLightRig rig;
  auto* dome = scene.find<Background>(background);
  if (!dome) dome = &scene.create<Background>("default dome");
  dome->setKind(BackgroundKind::Color);
  dome->setColor(Vec3(kDomeRadiance));
  dome->setIntensity(1.0f);
  rig.dome = dome->id();
  auto& follower = scene.create<Transform>("default camera light");
  auto& light = scene.create<Light>("default camera light");
  light.setKind(LightKind::Directional);
  light.setIntensity(kCameraLightIrradiance);
  light.setDirection(Vec3(0, 0, -1));  // the camera's view direction, once followed
  follower.addChild(light.id());
  if (parent->type() == ContainerType::Group)
    static_cast<Group*>(parent)->addChild(follower.id());
  else
    static_cast<Transform*>(parent)->addChild(follower.id());
  rig.follower = follower.id();
  rig.light = light.id();
  spdlog::warn("the scene has no lights: using the default rig (grey dome {} + camera light {} W/m^2)", kDomeRadiance,
               kCameraLightIrradiance);
  return rig;
}

void followCamera(Scene& scene, const DefaultLightRig& rig, const Mat4& cameraWorld) {
  if (auto* follower = scene.find<Transform>(rig.follower)) follower->setMatrix(cameraWorld);
}

}  // namespace tsr::sg
