#include "stereo_renderer.hpp"

#include <stdexcept>

namespace tsr::app {

namespace {

class LocalStereo final : public StereoRenderer {
 public:
  // A viewport per eye, sharing one converted scene: each keeps its own
  // samples (and history) instead of restarting at every other render.
  LocalStereo(const med::ViewportRegistry& registry, const med::ViewportSettings& settings)
      : left_(registry.create(settings, contexts_)), right_(registry.create(settings, contexts_)) {}

  void publish(SceneSession& session) override { session.publish(); }

  StereoPair render(const SceneSession& session, const med::View& centre, float separation, float zeroParallax,
                    const std::function<void(double)>& progress) override {
    StereoPair pair;
    med::RenderControl control;
    if (progress) control.progress = [&](double f) { progress(0.5 * f); };
    left_->render(session.replica, centre.eye(med::Eye::Left, separation, zeroParallax), pair.left, control);
    if (progress) control.progress = [&](double f) { progress(0.5 + 0.5 * f); };
    right_->render(session.replica, centre.eye(med::Eye::Right, separation, zeroParallax), pair.right, control);
    return pair;
  }

 private:
  med::ContextPool contexts_;
  std::unique_ptr<med::Viewport> left_, right_;
};

class ClusterStereo final : public StereoRenderer {
 public:
  ClusterStereo(const cluster::ClusterConfig& config, const cluster::ClientOptions& client, const SceneSession& session)
      : window_(config, client) {
    if (window_.connect(config.timeouts.connect) == 0)
      throw std::runtime_error("no cluster node could be reached: " + window_.status().front().lastError);
    window_.setContent(session.imported.root, session.imported.background);
  }

  void publish(SceneSession& session) override { window_.publish(session.source, session.publish()); }

  StereoPair render(const SceneSession&, const med::View& centre, float separation, float zeroParallax,
                    const std::function<void(double)>& progress) override {
    window_.setEyes(separation, zeroParallax);
    auto frame = window_.render(centre);  // both eyes at once, one on each node
    if (progress) progress(1.0);
    return {std::move(frame.left), std::move(frame.right)};
  }

 private:
  cluster::ClusterWindow window_;
};

}  // namespace

std::unique_ptr<StereoRenderer> localStereo(const med::ViewportRegistry& registry, med::ViewportSettings settings) {
  return std::make_unique<LocalStereo>(registry, settings);
}

std::unique_ptr<StereoRenderer> clusterStereo(const cluster::ClusterConfig& config,
                                              const cluster::ClientOptions& client, const SceneSession& session) {
  return std::make_unique<ClusterStereo>(config, client, session);
}

}  // namespace tsr::app
