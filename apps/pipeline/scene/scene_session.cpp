#include "scene/scene_session.hpp"

#include "backends.hpp"
#include "tsr/med/viewport_registry.hpp"
#include "tsr/sg/node_world.hpp"
#include "tsr/sg/shutter.hpp"

#include <cmath>

#include <spdlog/spdlog.h>

namespace tsr::app {

namespace {
// The depth along the view that pixel `at` sees in a session's published
// scene, from a one-sample render of that pixel alone by the path tracer,
// through the lens' centre.
float depthSeenAt(const SceneSession& session, const FocusOn& at) {
  const std::string option = "--focus-on " + std::to_string(at.x) + "," + std::to_string(at.y);
  if (at.x >= at.width || at.y >= at.height)
    throw std::invalid_argument(option + ": outside the " + std::to_string(at.width) + "x" + std::to_string(at.height) +
                                " image");
  med::ViewportRegistry registry;
  registerBackends(registry);
  med::ContextPool contexts;
  med::ViewportSettings settings;
  settings.backend = "embree";
  settings.root = session.imported.root;
  settings.background = session.imported.background;
  settings.parameters.set("spp", std::int64_t{1});
  const auto* camera = session.replica.scene().find<sg::Camera>(session.camera);
  med::View view = med::View::fromCamera(*camera, at.width, at.height).cropped({at.x, at.y, at.x + 1, at.y + 1});
  view.apertureRadius = 0.0f;
  med::FrameBuffer image;
  registry.create(settings, contexts)->render(session.replica, view, image);
  const float depth = image.depth.empty() ? INFINITY : image.depth.front();
  if (!(std::isfinite(depth) && depth > 0.0f))
    throw std::invalid_argument(option + ": that pixel sees no surface (only the background); focus on another "
                                         "or give --focus-distance");
  return depth;
}
}  // namespace

void SceneSession::load(const std::string& scene, const sg::ImportOptions& options, const ViewChoice& view) {
  sg::validate(view.look);  // before the import, which may take long
  imported = sg::importScene(source, scene, options);
  if (!view.camera.empty())
    camera = sg::chooseCamera(source, imported.cameras, view.camera);
  else
    camera = imported.cameras.empty() ? sg::addFramingCamera(source, imported.root) : imported.cameras.front();
  if (view.look.any()) camera = sg::applyLookOverride(source, imported.root, camera, view.look, imported.metresPerUnit);
  if (view.defaultLight && !sg::hasOwnLighting(source, imported.root, imported.background))
    rig = sg::addDefaultLightRig(source, imported.root, imported.background);
  if (view.focusOn) {
    // The same scene, loaded again without the focus and published to its
    // own replica, tells the depth; this session's edits stay pending.
    SceneSession probe;
    ViewChoice unfocused = view;
    unfocused.focusOn.reset();
    probe.load(scene, options, unfocused);
    probe.publish();
    const float depth = depthSeenAt(probe, *view.focusOn);
    source.find<sg::Camera>(camera)->setFocusDistance(depth);
    spdlog::info("--focus-on {},{}: focus distance {:.4g}", view.focusOn->x, view.focusOn->y, depth);
  }
}

bool SceneSession::shutterStaysOpen() const {
  const auto* lens = source.find<sg::Camera>(camera);
  return lens && sg::shutterStaysOpen(lens->shutterOpen(), lens->shutterClose());
}

void SceneSession::poseAnimations(double seconds, double frameInterval) {
  const bool open = shutterStaysOpen();
  for (const auto& animation : imported.animations)
    animation.apply(source, static_cast<float>(seconds), open ? static_cast<float>(frameInterval) : 0.0f);
}

sg::ChangeListPtr SceneSession::commit() {
  if (rig.active()) sg::followCamera(source, rig, sg::cameraWorldPose(source, camera));
  return source.commit();
}

sg::ChangeListPtr SceneSession::publish() {
  auto list = commit();
  replica.apply(list);
  return list;
}

}  // namespace tsr::app
