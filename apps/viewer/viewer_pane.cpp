#include "viewer_pane.hpp"

#include <algorithm>

#include "tsr/med/coverage/ranking.hpp"

namespace tsr::app {

namespace {
// What a progressive back-end shows while the camera moves, when asked to.
constexpr const char* kRasteriser = "vulkan";
// ... and what it shows the moment the camera rests (figure 5.6's middle step).
constexpr const char* kMode = "mode";
constexpr const char* kWhitted = "whitted";
}  // namespace

void ViewerPane::setParameter(const med::ViewportRegistry& registry, const std::string& name,
                              const med::ParameterValue& value) {
  med::Parameters one;
  one.set(name, value);
  registry.requireDeclared(one, registry.backends());
  defaults_.parameters.set(name, value);
  for (auto& [backend, viewport] : viewports_)
    if (viewport->capabilities().parameters.declares(name) || isRemote(backend)) viewport->setParameter(name, value);
  if (whitted_ && name != kMode && whitted_->capabilities().parameters.declares(name))
    whitted_->setParameter(name, value);
  restart_ = true;
}

void ViewerPane::resetScene(const med::ViewportSettings& defaults) {
  const med::Parameters kept = defaults_.parameters;
  defaults_ = defaults;
  defaults_.parameters = kept;
  viewports_.clear();
  whitted_.reset();
  showWhitted_ = false;
  remoteBackends_.clear();
  frame_ = {};
  stats_ = {};
  samples_ = 0;
  restart_ = true;
}

med::Viewport& ViewerPane::viewport(const std::string& backend, const med::ViewportRegistry& registry,
                                    med::ContextPool& contexts) {
  auto it = viewports_.find(backend);
  if (it == viewports_.end()) {
    med::ViewportSettings settings = defaults_;
    settings.backend = backend;
    settings.parameters = registry.parametersFor(backend, defaults_.parameters);
    std::unique_ptr<med::Viewport> made = remote_ ? remote_(settings) : nullptr;
    if (made)
      remoteBackends_.insert(backend);
    else
      made = registry.create(settings, contexts);
    it = viewports_.emplace(backend, std::move(made)).first;
  }
  return *it->second;
}

med::Viewport* ViewerPane::whittedViewport(const std::string& backend, const med::ViewportRegistry& registry,
                                           med::ContextPool& contexts) {
  if (isRemote(backend) || !registry.capabilities(backend).parameters.declares(kMode)) return nullptr;
  if (!whitted_ || whitted_->backend() != backend) {
    med::ViewportSettings settings = defaults_;
    settings.backend = backend;
    settings.parameters = registry.parametersFor(backend, defaults_.parameters);
    settings.parameters.set(kMode, std::string(kWhitted));
    whitted_ = registry.create(settings, contexts);  // shares the path tracer's converted scene
  }
  return whitted_.get();
}

void ViewerPane::render(const med::ViewportRegistry& registry, med::ContextPool& contexts, const sg::Replica& replica,
                        const med::View& view, bool sceneChanged, const ConvergenceSettings& convergence) {
  std::string backend = backend_;
  const bool standIn = registry.capabilities(backend).progressive && convergence.rasterWhileMoving &&
                       registry.has(kRasteriser) && backend != kRasteriser;
  if (standIn && convergence.cameraMoving) backend = kRasteriser;
  const bool switched = backend != shown_;
  // The camera came to rest: the rasteriser stood in for this back-end until now.
  const bool rested = standIn && switched && shown_ == kRasteriser && backend == backend_;
  shown_ = backend;
  if (sceneChanged || !(view == lastView_)) {
    restart_ = true;
    showWhitted_ = false;
  }
  lastView_ = view;
  med::Viewport& vp = viewport(backend, registry, contexts);

  med::RenderControl control;
  control.interactive = true;
  control.outputs = std::vector<std::string>{};
  // The ranked list and picking read object ids, where the back-end offers them.
  if (const auto offered = vp.outputNames(); std::find(offered.begin(), offered.end(), med::kIdOutput) != offered.end())
    control.outputs->push_back(med::kIdOutput);

  const bool restarted = restart_ || switched;
  const bool reportSwitch = switched;
  restart_ = false;
  const bool sized = frame_.width == view.region.width() && frame_.height == view.region.height();
  // Asked of the viewport once it exists (a node's stand-in declares none).
  shownProgressive_ = vp.capabilities().progressive && !isRemote(backend);
  if (!shownProgressive_) {
    converging_ = false;
    if (restarted || !sized) stats_ = vp.render(replica, view, frame_, control);  // else the image stands
    if (reportSwitch) switchReport_.emplace(backend, stats_);
    return;
  }
  if (rested) {
    if (med::Viewport* whitted = whittedViewport(backend, registry, contexts)) {
      stats_ = whitted->render(replica, view, whittedFrame_, control);
      showWhitted_ = true;
      samples_ = 0;
      if (reportSwitch) switchReport_.emplace(backend, stats_);
      restart_ = true;  // the path tracer starts on the next frame
      converging_ = true;
      return;
    }
  }
  // The path tracer converges one pass a frame: it is asked for the samples
  // it has plus one (it restarts by itself when the view, the scene or its
  // settings changed, and then renders that one sample, paused or not).
  const std::uint32_t previous = samples_;
  if (restarted) samples_ = 0;
  const std::uint32_t limit = convergence.sampleLimit;
  converging_ = samples_ < limit && !convergence.paused;
  if (!converging_ && !restarted && sized) return;
  const std::uint32_t want = std::min(limit, std::max<std::uint32_t>(samples_ + 1, 1));
  vp.setParameter("spp", std::int64_t(want));
  stats_ = vp.render(replica, view, frame_, control);
  if (reportSwitch) switchReport_.emplace(backend, stats_);
  samples_ = stats_.samples;
  if (showWhitted_ && samples_ >= std::min(kWhittedUntil, limit)) showWhitted_ = false;
  // Rates over the whole convergence so far (filter steps included), not
  // one frame's: a filter frame would read as a stall.
  if (samples_ < previous || samples_ <= 1) rates_ = {};  // the accumulation started again
  rates_.seconds += stats_.seconds - stats_.syncSeconds;
  rates_.rays += stats_.rays;
  if (rates_.seconds > 0) {
    samplesPerSecond_ = double(samples_) / rates_.seconds;
    raysPerSecond_ = double(rates_.rays) / rates_.seconds;
  }
}

void ViewerPane::keepUp(const sg::Replica& replica) {
  if (++editsSinceKeepUp_ < 64) return;
  editsSinceKeepUp_ = 0;
  for (auto& [backend, viewport] : viewports_)
    if (backend != shown_) viewport->synchronize(replica);
}

std::optional<std::pair<std::string, med::RenderStats>> ViewerPane::takeSwitchReport() {
  auto report = std::move(switchReport_);
  switchReport_.reset();
  return report;
}

const med::FrameBuffer& ViewerPane::renderWithOutputs(const med::ViewportRegistry& registry, med::ContextPool& contexts,
                                                      const sg::Replica& replica, const med::View& view) {
  med::Viewport& vp = viewport(shown_.empty() ? backend_ : shown_, registry, contexts);
  med::RenderControl control;  // outputs unset: all it offers
  const bool progressive = vp.capabilities().progressive && !isRemote(vp.backend());
  if (progressive) vp.setParameter("spp", std::int64_t(std::max<std::uint32_t>(samples_, 1)));
  stats_ = vp.render(replica, view, frame_, control);
  if (progressive) samples_ = stats_.samples;
  return frame_;
}

}  // namespace tsr::app
