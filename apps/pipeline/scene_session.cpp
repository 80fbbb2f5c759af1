#include "scene_session.hpp"

#include "tsr/sg/node_world.hpp"

namespace tsr::app {

void SceneSession::load(const std::string& scene, const sg::ImportOptions& options, const ViewChoice& view) {
  sg::validate(view.look);  // before the import, which may take long
  imported = sg::importScene(source, scene, options);
  if (!view.camera.empty())
    camera = sg::chooseCamera(source, imported.cameras, view.camera);
  else
    camera = imported.cameras.empty() ? sg::addFramingCamera(source, imported.root) : imported.cameras.front();
  if (view.look.any()) camera = sg::applyLookOverride(source, imported.root, camera, view.look);
  if (view.defaultLight && !sg::hasOwnLighting(source, imported.root, imported.background))
    rig = sg::addDefaultLightRig(source, imported.root, imported.background);
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
