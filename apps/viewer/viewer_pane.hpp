#pragma once
// One viewport of the viewer's window: a column of it, rendered by the
// back-end the user picked. Every back-end it has shown keeps its viewport
// (and so its converted scene) alive, so switching back catches up with
// the change list instead of converting the scene again.
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>

#include "layers.hpp"
#include "tsr/med/viewport_registry.hpp"

namespace tsr::app {

struct ConvergenceSettings {
  std::uint32_t sampleLimit = 1024;
  bool paused = false;
  bool rasterWhileMoving = false;  // figure 5.6 of the seed
  bool cameraMoving = false;
};

class ViewerPane {
 public:
  ViewerPane(std::string backend, med::ViewportSettings defaults)
      : defaults_(std::move(defaults)), backend_(std::move(backend)) {}

  const std::string& backend() const { return backend_; }
  // The back-end shown from the next frame on; its viewport is created on
  // first use through the registry.
  void setBackend(const std::string& backend) { backend_ = backend; }
  // Viewports rendered elsewhere (a cluster's nodes): asked first for each
  // back-end; those it makes render whole frames, like a rasteriser.
  void setRemote(RemoteLayers remote) { remote_ = std::move(remote); }
  bool isRemote(const std::string& backend) const { return remoteBackends_.count(backend) != 0; }
  // Sets a parameter of this pane's viewports whose back-end takes it (those
  // alive and those to come); one no back-end of the registry takes, or a
  // bad value, throws med::ParameterError and changes nothing.
  void setParameter(const med::ViewportRegistry& registry, const std::string& name, const med::ParameterValue& value);
  const med::Parameters& parameters() const { return defaults_.parameters; }
  // A new scene: viewports of the old one are dropped.
  void resetScene(const med::ViewportSettings& defaults);

  // Renders one frame's worth: a rasteriser or coverage image whole, the
  // path tracer one more pass towards the sample limit (nothing once there
  // or while paused). `sceneChanged`: the replica moved on since last frame.
  void render(const med::ViewportRegistry& registry, med::ContextPool& contexts, const sg::Replica& replica,
              const med::View& view, bool sceneChanged, const ConvergenceSettings& convergence);
  // Renders again with every output the shown back-end offers (for a
  // screenshot with AOVs); a converged path tracer only copies them out.
  const med::FrameBuffer& renderWithOutputs(const med::ViewportRegistry& registry, med::ContextPool& contexts,
                                            const sg::Replica& replica, const med::View& view);

  // Keeps the viewports not shown within the replica's change log (it holds
  // 256 lists), so switching back syncs rather than converts. Call after
  // each published edit; it syncs them every 64th.
  void keepUp(const sg::Replica& replica);
  // What catching up took on the first frame after the last switch, once.
  std::optional<std::pair<std::string, med::RenderStats>> takeSwitchReport();

  // The picture shown: the Whitted image while it bridges (below), else the last frame.
  const med::FrameBuffer& frame() const { return showWhitted_ ? whittedFrame_ : frame_; }
  // Figure 5.6's middle step: with rasterWhileMoving, the first frame the
  // camera rests after moving renders one Whitted-style image (sharp
  // reflections and hard shadows, mode=whitted), shown while the path
  // tracer's own image gathers its first kWhittedUntil samples: 2, where
  // the pixel filter, the viewer's default, gives its first preview.
  bool showingWhitted() const { return showWhitted_; }
  static constexpr std::uint32_t kWhittedUntil = 2;
  const med::RenderStats& stats() const { return stats_; }
  // The back-end of the last frame (the rasteriser while moving, with that option).
  const std::string& shownBackend() const { return shown_; }
  // Whether the last frame's back-end accumulates samples here (not remote).
  bool progressive() const { return shownProgressive_; }
  std::uint32_t samples() const { return shownProgressive_ ? samples_ : 0; }
  // Since the image last restarted.
  double samplesPerSecond() const { return samplesPerSecond_; }
  double raysPerSecond() const { return raysPerSecond_; }
  bool converging() const { return converging_; }
  // Viewports created so far, by back-end (the ones kept alive).
  std::size_t viewportCount() const { return viewports_.size(); }
  bool hasViewport(const std::string& backend) const { return viewports_.count(backend) != 0; }

 private:
  med::Viewport& viewport(const std::string& backend, const med::ViewportRegistry& registry,
                          med::ContextPool& contexts);
  // The Whitted viewport of a back-end that offers mode=whitted, else null.
  med::Viewport* whittedViewport(const std::string& backend, const med::ViewportRegistry& registry,
                                 med::ContextPool& contexts);

  med::ViewportSettings defaults_;
  std::string backend_;
  std::string shown_;
  bool shownProgressive_ = false;
  std::map<std::string, std::unique_ptr<med::Viewport>> viewports_;
  RemoteLayers remote_;
  std::set<std::string> remoteBackends_;
  med::FrameBuffer frame_;
  std::unique_ptr<med::Viewport> whitted_;
  med::FrameBuffer whittedFrame_;
  bool showWhitted_ = false;
  med::RenderStats stats_;
  med::View lastView_;
  std::uint32_t samples_ = 0;
  std::uint32_t editsSinceKeepUp_ = 0;
  std::optional<std::pair<std::string, med::RenderStats>> switchReport_;
  bool restart_ = true;
  bool converging_ = false;
  struct Rates {
    double seconds = 0;  // rendering since the last restart
    std::uint64_t rays = 0;
  } rates_;
  double samplesPerSecond_ = 0, raysPerSecond_ = 0;
};

}  // namespace tsr::app
