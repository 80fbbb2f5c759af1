#pragma once
// The application side of a render: the authoring scene loaded from a file
// or a built-in, the camera to look through, and a replica fed by commits
// (the render thread's copy, in the DESIGN's words).
#include <string>

#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/replica.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::app {

struct SceneSession {
  sg::Scene source;
  sg::ImportResult imported;
  sg::ContainerId camera = sg::kNoContainer;
  sg::Replica replica;

  // Imports `scene`; adds a camera framing the bounds when it has none.
  // Throws sg::ImportError.
  void load(const std::string& scene, const sg::ImportOptions& options = {});
  // Commits the frame's edits and applies them to the replica.
  sg::ChangeListPtr publish();
};

}  // namespace tsr::app
