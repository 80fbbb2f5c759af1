#pragma once
// A scene the quality harness renders: imported once, followed by a replica,
// with a pool of contexts kept alive by an anchor viewport so that every
// fresh viewport on it reuses one converted scene (conversion and BVH build
// stay out of the timings).
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tsr/med/frame_buffer.hpp"
#include "tsr/med/viewport_registry.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/replica.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::quality {

struct Shot {
  med::FrameBuffer image;
  double seconds = 0;       // the render call without catching up (conversion, BVH)
  double totalSeconds = 0;  // the whole render call
  std::uint32_t samples = 0;
};

// When a scene is rendered and how long its shutter stays open: the
// animations are posed at `time` (seconds) with their motion over the next
// `frameInterval` seconds, and the camera's shutter opens and closes at
// these fractions of that interval. The default is an instant at time 0
// with the scene as imported.
struct Motion {
  float time = 0.0f;
  float frameInterval = 0.0f;
  float shutterOpen = 0.0f, shutterClose = 0.0f;
  bool moves() const { return frameInterval > 0.0f && shutterClose > shutterOpen; }
};

class QualityScene {
 public:
  // key: file-name-safe name for caches; source: a path or builtin:NAME.
  // glossy: the red wall's material becomes a GGX conductor (roughness 0.2).
  // environment: a latitude-longitude float image (EXR, PFM, HDR) that
  // lights the scene instead of its background; empty: none. A scene with
  // no light of its own gets the default light rig, as the programs give
  // it, and one with no camera a framing camera. motion: a shutter that
  // stays open poses the animations at motion.time with their motion and
  // opens the camera's shutter; otherwise the scene stays as imported.
  QualityScene(std::string key, std::string label, const std::string& source, bool glossy,
               const med::ViewportRegistry& registry, const std::string& environment = {}, const Motion& motion = {});

  const std::string& key() const { return key_; }
  const std::string& label() const { return label_; }
  const Motion& motion() const { return motion_; }

  // A fresh viewport over the scene with `parameters` (backend embree).
  std::unique_ptr<med::Viewport> viewport(const med::Parameters& parameters);
  // Renders `viewport` at size x size; throws what the viewport throws.
  // `outputs`: named outputs to fill besides colour (and "blend" if asked).
  Shot render(med::Viewport& viewport, std::uint32_t size, bool wantBlend = false,
              const std::vector<std::string>& outputs = {});
  // The same at width x height.
  Shot renderSized(med::Viewport& viewport, std::uint32_t width, std::uint32_t height,
                   const std::vector<std::string>& outputs = {}, bool wantBlend = false);

  // Turns the camera from where it was imported by `degrees` about the
  // vertical (world +Y) axis through the point `pivotDistance` ahead of it
  // (an orbit, as the viewer's), then commits.
  void orbit(float degrees, float pivotDistance);

  // Poses the scene's animations at `seconds` (with their motion over the
  // frame interval when the shutter stays open), scales every light's
  // intensity by `lightScale` (a light switch) and moves the camera `pan`
  // scene units to its right of where it was imported (a moving camera),
  // then commits.
  void pose(float seconds, float lightScale = 1.0f, float pan = 0.0f);

  // Renders frames 0..frames-1 of the animation through a viewport that
  // looks ahead (Viewport::lookahead, the photon viewport): frame f is posed
  // by pose(f) in a replica ahead and prepared `lookahead` frames before it
  // is shown from a second replica. Each shot's seconds include its share of
  // the prepare() calls (the photon passes). Leaves the scene at the last frame.
  std::vector<Shot> renderAhead(med::Viewport& viewport, std::uint32_t size, int frames,
                                const std::function<void(int frame)>& pose, const std::vector<std::string>& outputs);

 private:
  // The animations at `seconds`, with their motion over the frame interval
  // when the shutter stays open (Transform::frameMotion).
  void poseAnimations(float seconds);

  std::string key_, label_;
  const med::ViewportRegistry& registry_;
  sg::Scene source_;
  sg::ImportResult imported_;
  sg::Replica replica_;
  sg::ChangeListPtr lastCommit_;  // of the last pose()
  med::ContextPool contexts_;
  std::unique_ptr<med::Viewport> anchor_;
  std::vector<std::pair<sg::ContainerId, float>> lightIntensities_;  // as imported
  std::optional<glm::mat4> cameraPose_;                              // as imported
  sg::ContainerId camera_ = sg::kNoContainer;
  Motion motion_;
};

}  // namespace tsr::quality
