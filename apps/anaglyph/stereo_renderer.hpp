#pragma once
// Where the two eyes render: here, one viewport (one converted scene)
// rendering both eye views in turn; or on cluster nodes in stereo mode,
// left eye on the first node and right eye on the second (both on one
// node when one is given). Either way the application's scene reaches the
// renderers as change lists, each frame.
#include <functional>
#include <memory>
#include <string>

#include "scene/scene_session.hpp"
#include "tsr/cluster/cluster_window.hpp"
#include "tsr/med/context_pool.hpp"
#include "tsr/med/viewport_registry.hpp"

namespace tsr::app {

struct StereoPair {
  med::FrameBuffer left, right;
};

class StereoRenderer {
 public:
  virtual ~StereoRenderer() = default;
  // Commits the session's edits and hands them to the renderers.
  virtual void publish(SceneSession& session) = 0;
  // Both eyes of `centre` (the full image of the cyclopean view);
  // `progress` (may be empty) hears 0..1 over both.
  virtual StereoPair render(const SceneSession& session, const med::View& centre, float separation, float zeroParallax,
                            const std::function<void(double)>& progress = {}) = 0;
};

std::unique_ptr<StereoRenderer> localStereo(const med::ViewportRegistry& registry, med::ViewportSettings settings);

// Connects to `config` (mode stereo); throws when no node answers.
std::unique_ptr<StereoRenderer> clusterStereo(const cluster::ClusterConfig& config,
                                              const cluster::ClientOptions& client, const SceneSession& session);

}  // namespace tsr::app
