#include "embree_viewport.hpp"

#include "embree_parameters.hpp"
#include "tsr/med/view_translation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace tsr::med::embree_mediator {

namespace {
constexpr std::uint32_t kLargestGrownPass = 8;
}  // namespace

EmbreeViewport::EmbreeViewport(ViewportSettings settings, std::shared_ptr<EmbreeContext> context)
    : Viewport(std::move(settings)), context_(std::move(context)) {}

std::vector<std::string> EmbreeViewport::outputNames() const {
  std::vector<std::string> names = accumulatedOutputNames();
  if (FilterSettings::from(settings_.parameters).usesPixelFilter()) names.emplace_back(kBlendOutput);
  return names;
}

std::vector<std::string> EmbreeViewport::resolveInputs() const {
  const FilterSettings filter = FilterSettings::from(settings_.parameters);
  std::vector<std::string> inputs;
  if (filter.usesPixelFilter()) inputs = pixelFilterInputs();
  if (filter.usesDenoiser()) inputs = denoiseInputs();
  return inputs;
}

std::vector<std::string> EmbreeViewport::resolveOutputs() const {
  if (!FilterSettings::from(settings_.parameters).usesPixelFilter()) return {};
  return {kBlendOutput};
}

// A frame assembled by the caller (a cluster's tiles) belongs to no
// accumulation of this viewport: epoch 0, which no FrameBuffer has.
void EmbreeViewport::resolve(FrameBuffer& frame) {
  const FilterSettings filter = FilterSettings::from(settings_.parameters);
  if (filter.usesPixelFilter()) pixelFilter_.resolve(frame, filter, true, frame.outputs.count(kBlendOutput) != 0, 0);
  if (filter.usesDenoiser()) denoiser_.resolve(frame, filter.denoise, true, 0);
}

SceneAdapter::Update EmbreeViewport::synchronize(const sg::Replica& replica) {
  std::lock_guard lock(context_->mutex);
  return context_->adapter.catchUp(replica);
}

// Pixel filtering's inputs of a finished render: flash samples topped up,
// the buffers written as outputs.
void EmbreeViewport::writeFilterInputs(embree::Scene& scene, const embree::Camera& camera, const embree::Region& traced,
                                       const FilterSettings& filter, FrameBuffer& full) {
  embree::FrameBuffer& fb = *accumulation_;
  const std::uint32_t flash = flashSamplesFor(fb.sampleCount(0, 0));
  if (fb.rangeSamples(0, 0) < flash)
    renderer_.renderFlashPass(scene, camera, traced, fb, flash - fb.rangeSamples(0, 0));
  writePixelFilterInputs(fb, filter.pathClass, full, filter.mode == FilterMode::Hybrid ? radiance_.get() : nullptr);
}

// Resolved here unless the caller assembles the frame from regions (then
// it resolves, and the inputs go to it).
void EmbreeViewport::resolveLocally(const FilterSettings& filter, std::uint32_t spp, bool traced, FrameBuffer& out,
                                    const RenderControl& control) {
  if (!control.resolve) return;
  // Filter on the 4, 8, 16, ... schedule, and when the image is complete
  // at another count (a batch render of 12 spp) if that at least doubles
  // the samples of the last filtered buffer; frames in between blend new
  // samples with it. A viewer that asks for one more sample each frame so
  // filters at 2, 4, 8, 16, ... and not at every frame. One sample has no
  // variance estimate to filter by.
  // The denoiser follows the same schedule, and keeps showing its last
  // image in between (its guides need no fresh samples to be blended).
  // A reprojected history is filtered at each of its first new samples (the
  // view moves, a frame or two each): its inherited samples give the
  // variance one traced sample lacks. Then the schedule takes over. (The
  // filters' own record of the count they last saw includes the inherited
  // samples, so it cannot tell a call that traced nothing: `traced` does.)
  const std::uint32_t samples = accumulation_->tracedCount(0, 0);
  const std::uint64_t epoch = accumulation_->epoch();
  const auto last = filter.usesDenoiser() ? denoiser_.denoisedAt(epoch) : pixelFilter_.filteredAt(epoch);
  const bool complete = samples >= spp && (!last || samples >= 2 * *last);
  const bool scheduled = samples >= 2 && (embree::isFilterFrame(samples) || complete);
  const bool due = (scheduled || (accumulation_->carriesHistory() && samples < 4 && traced)) && last != samples;
  if (filter.usesDenoiser()) {
    if (due || last) denoiser_.resolve(out, filter.denoise, due, epoch);
  } else if (due || last) {
    pixelFilter_.resolve(out, filter, due, control.wants(kBlendOutput), epoch);
  }
  auto explicitlyWanted = [&](const std::string& name) {
    return control.outputs &&
           std::find(control.outputs->begin(), control.outputs->end(), name) != control.outputs->end();
  };
  for (const auto& name : filter.usesDenoiser() ? denoiseInputs() : pixelFilterInputs())
    if (!explicitlyWanted(name)) out.outputs.erase(name);
}

namespace {

// The pixels [x0, x0 + w) x [y0, y0 + h) of `full`, every output included.
FrameBuffer crop(FrameBuffer full, std::uint32_t x0, std::uint32_t y0, std::uint32_t w, std::uint32_t h) {
  if (x0 == 0 && y0 == 0 && w == full.width && h == full.height) return full;
  FrameBuffer out(w, h);
  auto copy = [&](auto& to, const auto& from) {
    to.resize(std::size_t{w} * h);
    for (std::uint32_t y = 0; y < h; ++y)
      std::copy_n(from.begin() + full.index(x0, y0 + y), w, to.begin() + out.index(0, y));
  };
  copy(out.colour, full.colour);
  copy(out.depth, full.depth);
  for (const auto& [name, image] : full.outputs) copy(out.outputs[name], image);
  return out;
}

}  // namespace

// mode=whitted: one Whitted sample per pixel, rendered once for a scene,
// camera and region and shown as it is (spp and the filters do not apply).
void EmbreeViewport::renderWhitted(const embree::Camera& camera, const embree::Region& region, FrameBuffer& out,
                                   const RenderControl& control, std::chrono::steady_clock::time_point start,
                                   RenderStats& stats) {
  if (!whitted_ || whitted_->width() != region.regionWidth() || whitted_->height() != region.regionHeight())
    whitted_ = std::make_unique<embree::WhittedImage>(region.regionWidth(), region.regionHeight());
  embree::Scene& scene = context_->adapter.scene();
  stats.syncSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!(control.cancel && control.cancel->load()))
    stats.rays += renderer_.renderWhitted(scene, camera, region, *whitted_).rays;
  if (control.progress) control.progress(1.0);
  stats.samples = whitted_->complete() ? 1 : 0;
  writeWhittedFrame(*whitted_, control, out);
}

RenderStats EmbreeViewport::render(const sg::Replica& replica, const View& view, FrameBuffer& out,
                                   const RenderControl& control) {
  view.validate();
  const auto start = std::chrono::steady_clock::now();
  const auto spp = static_cast<std::uint32_t>(embreeParameters().integer(settings_.parameters, "spp"));
  renderer_.setSettings(renderSettingsFrom(settings_.parameters, control.frame));
  const FilterSettings filter = FilterSettings::from(settings_.parameters);
  const bool radiance = filter.usesRadianceFilter();

  std::lock_guard lock(context_->mutex);
  RenderStats stats;
  stats.update = context_->adapter.catchUp(replica);

  const embree::Camera camera = cameraOf(view);
  const embree::Region region = regionOf(view);
  if (embreeParameters().choice(settings_.parameters, "mode") == "whitted") {
    renderWhitted(camera, region, out, control, start, stats);
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return stats;
  }
  // Radiance filtering gathers samples up to maxRadius pixels away in every
  // frame: a region (a cluster tile) is traced with a halo that wide, so
  // its pixels match the whole frame's (within backends/embree/README.md's tolerance).
  embree::Region traced = region;
  if (radiance) {
    const auto halo = static_cast<std::uint32_t>(std::ceil(filter.radiance.maxRadius));
    traced.x0 = region.x0 > halo ? region.x0 - halo : 0;
    traced.y0 = region.y0 > halo ? region.y0 - halo : 0;
    traced.x1 = std::min(region.width, region.x1 + halo);
    traced.y1 = std::min(region.height, region.y1 + halo);
  }
  if (!accumulation_ || accumulation_->width() != traced.regionWidth() ||
      accumulation_->height() != traced.regionHeight())
    accumulation_ = std::make_unique<embree::FrameBuffer>(traced.regionWidth(), traced.regionHeight());
  if (radiance &&
      (!radiance_ || radiance_->width() != traced.regionWidth() || radiance_->height() != traced.regionHeight()))
    radiance_ = std::make_unique<embree::RadianceAccumulator>(traced.regionWidth(), traced.regionHeight());

  // Progressive: passes until the target sample count of samples traced
  // for this view (a reprojected history comes on top). The back-end alone
  // decides, once a frame, whether the samples held still fit the scene,
  // camera, region and settings: it commits what the catch-up changed
  // (building acceleration structures) and restarts the accumulation if
  // not, and the filters see the new epoch; a converged image is reused.
  embree::Scene& scene = context_->adapter.scene();
  renderer_.restartIfStale(scene, camera, traced, *accumulation_,
                           radiance ? embree::Estimator::Radiance : embree::Estimator::Paths);
  stats.syncSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  embree::RenderSettings settings = renderer_.settings();
  // Unless samplesPerPass is given, passes grow 1, 2, 4, 8 samples per pixel:
  // the first image is ready after one sample, and later passes keep a
  // pixel's samples back to back (its paths find the same BVH nodes in
  // cache) and pay the per-pass costs less often. Which pass a sample falls
  // in does not change it: samples are seeded by their index. A radiance
  // pass is one sample: its filter step works on one sample per pixel.
  const bool growPasses = !settings_.parameters.has("samplesPerPass");
  std::uint32_t passSize = settings.samplesPerPass;
  bool passRan = false;  // in this call
  for (;;) {
    embree::FrameBuffer& fb = *accumulation_;
    const std::uint32_t done = fb.tracedCount(0, 0);
    if (done >= spp) break;
    if (control.cancel && control.cancel->load()) break;
    if (growPasses && !radiance) {
      settings.samplesPerPass = std::min(passSize, spp - done);
      renderer_.setSettings(settings);
      passSize = std::min(passSize * 2, kLargestGrownPass);
    }
    auto pass = radiance ? renderer_.renderRadiancePass(scene, camera, traced, fb, *radiance_, filter.radiance)
                         : renderer_.renderPass(scene, camera, traced, fb);
    stats.rays += pass.rays;
    passRan = true;
    if (control.progress) control.progress(std::min(1.0, fb.tracedCount(0, 0) / double(spp)));
    if (!pass.completed) break;
  }
  stats.samples = accumulation_->tracedCount(0, 0);

  const embree::FrameBuffer& fb = *accumulation_;
  FrameBuffer full = accumulatedFrame(fb, control);
  if (radiance) {
    const auto shown = radiance_->radianceImage(fb);
    for (std::size_t i = 0; i < shown.size(); ++i) full.colour[i] = glm::vec4(shown[i], full.colour[i].a);
  }
  if (filter.usesPixelFilter() && stats.samples > 0) writeFilterInputs(scene, camera, traced, filter, full);
  if (filter.usesDenoiser() && stats.samples > 0) writeDenoiseInputs(fb, full);
  out =
      crop(std::move(full), region.x0 - traced.x0, region.y0 - traced.y0, region.regionWidth(), region.regionHeight());
  if ((filter.usesPixelFilter() || filter.usesDenoiser()) && stats.samples > 0)
    resolveLocally(filter, spp, passRan, out, control);
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace tsr::med::embree_mediator
