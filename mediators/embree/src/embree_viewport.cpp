#include "embree_viewport.hpp"

#include <algorithm>
#include <chrono>

namespace tsr::med::embree_mediator {

namespace {
constexpr std::uint32_t kLargestGrownPass = 8;
constexpr const char* kAlbedo = "albedo";
constexpr const char* kNormal = "normal";
constexpr const char* kDirect = "direct";
constexpr const char* kIndirect = "indirect";
constexpr const char* kVariance = "variance";
}  // namespace

EmbreeViewport::EmbreeViewport(ViewportSettings settings, std::shared_ptr<EmbreeContext> context)
    : Viewport(std::move(settings)), context_(std::move(context)) {}

embree::RenderSettings EmbreeViewport::renderSettings() const {
  const Parameters& p = settings_.parameters;
  embree::RenderSettings s;
  s.seed = static_cast<std::uint64_t>(p.getInt("seed", 0, 0));
  s.maxDepth = static_cast<std::uint32_t>(p.getInt("maxDepth", 8, 0, 1024));
  if (p.getBool("directOnly", false)) s.maxDepth = 1;
  s.samplesPerPass = static_cast<std::uint32_t>(p.getInt("samplesPerPass", 1, 1, 4096));
  s.threads = static_cast<int>(p.getInt("threads", 0, 0, 4096));
  return s;
}

std::vector<std::string> EmbreeViewport::outputNames() const {
  std::vector<std::string> names{kAlbedo, kNormal, kDirect, kIndirect, kVariance};
  if (FilterSettings::from(settings_.parameters).usesPixelFilter()) names.push_back(kBlendOutput);
  return names;
}

std::vector<std::string> EmbreeViewport::resolveInputs() const {
  return FilterSettings::from(settings_.parameters).usesPixelFilter() ? pixelFilterInputs() : std::vector<std::string>{};
}

void EmbreeViewport::resolve(FrameBuffer& frame) {
  const FilterSettings filter = FilterSettings::from(settings_.parameters);
  if (filter.usesPixelFilter()) pixelFilter_.resolve(frame, filter, true, frame.outputs.count(kBlendOutput) != 0);
}

SceneAdapter::Update EmbreeViewport::synchronize(const sg::Replica& replica) {
  std::lock_guard lock(context_->mutex);
  return context_->adapter.catchUp(replica);
}

// Pixel filtering of a finished pass: flash samples topped up, inputs
// written as outputs; resolved here unless the caller assembles the frame
// from regions (then it resolves, and the inputs go to it).
void EmbreeViewport::filterPixels(embree::Scene& scene, const embree::Camera& camera, const embree::Region& region,
                                  const FilterSettings& filter, std::uint32_t spp, FrameBuffer& out,
                                  const RenderControl& control) {
  embree::FrameBuffer& fb = *accumulation_;
  const std::uint32_t samples = fb.sampleCount(0, 0);
  const std::uint32_t flash = flashSamplesFor(samples);
  if (fb.rangeSamples(0, 0) < flash) renderer_.renderFlashPass(scene, camera, region, fb, flash - fb.rangeSamples(0, 0));
  writePixelFilterInputs(fb, filter.pathClass, out);
  if (!control.resolve) return;
  // Filter on the 4, 8, 16, ... schedule and when the image is complete;
  // frames in between blend new samples with the last filtered buffer.
  const bool due = (embree::isFilterFrame(samples) || samples >= spp) && pixelFilter_.filteredAt() != samples;
  pixelFilter_.resolve(out, filter, due, control.wants(kBlendOutput));
  auto explicitlyWanted = [&](const std::string& name) {
    return control.outputs && std::find(control.outputs->begin(), control.outputs->end(), name) != control.outputs->end();
  };
  for (const auto& name : pixelFilterInputs())
    if (!explicitlyWanted(name)) out.outputs.erase(name);
}

RenderStats EmbreeViewport::render(const sg::Replica& replica, const View& view, FrameBuffer& out,
                                   const RenderControl& control) {
  view.validate();
  const auto start = std::chrono::steady_clock::now();
  const auto spp = static_cast<std::uint32_t>(settings_.parameters.getInt("spp", 16, 1, 1 << 20));
  renderer_.setSettings(renderSettings());
  const FilterSettings filter = FilterSettings::from(settings_.parameters);
  if (filter.mode == FilterMode::Radiance || filter.mode == FilterMode::Hybrid)
    throw ParameterError("parameter filter: radiance filtering is not available yet");

  std::lock_guard lock(context_->mutex);
  RenderStats stats;
  stats.update = context_->adapter.catchUp(replica);

  embree::Camera camera{view.cameraToWorld, view.left, view.right, view.bottom, view.top, view.nearPlane};
  embree::Region region{view.width, view.height, view.region.x0, view.region.y0, view.region.x1, view.region.y1};
  if (!accumulation_ || accumulation_->width() != region.regionWidth() ||
      accumulation_->height() != region.regionHeight())
    accumulation_ = std::make_unique<embree::FrameBuffer>(region.regionWidth(), region.regionHeight());

  // Progressive: passes until the target sample count. The back-end restarts
  // accumulation by itself when the scene, camera, region or settings
  // changed; a converged image is reused only if none of them did.
  embree::Scene& scene = context_->adapter.scene();
  scene.commit();  // builds the acceleration structures the catch-up touched
  stats.syncSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  embree::RenderSettings settings = renderer_.settings();
  Accumulated now{&scene, scene.version(), camera, region, settings.seed, settings.maxDepth};
  bool stale = accumulated_ != now;
  if (stale) pixelFilter_.forget();
  // Unless samplesPerPass is given, passes grow 1, 2, 4, 8 samples per pixel:
  // the first image is ready after one sample, and later passes keep a
  // pixel's samples back to back (its paths find the same BVH nodes in
  // cache) and pay the per-pass costs less often. Which pass a sample falls
  // in does not change it: samples are seeded by their index.
  const bool growPasses = !settings_.parameters.has("samplesPerPass");
  std::uint32_t passSize = settings.samplesPerPass;
  for (;;) {
    embree::FrameBuffer& fb = *accumulation_;
    const std::uint32_t done = stale ? 0 : fb.sampleCount(0, 0);
    if (done >= spp) break;
    if (control.cancel && control.cancel->load()) break;
    stale = false;
    accumulated_ = now;
    if (growPasses) {
      settings.samplesPerPass = std::min(passSize, spp - done);
      renderer_.setSettings(settings);
      passSize = std::min(passSize * 2, kLargestGrownPass);
    }
    auto pass = renderer_.renderPass(scene, camera, region, fb);
    stats.rays += pass.rays;
    if (control.progress) control.progress(std::min(1.0, fb.sampleCount(0, 0) / double(spp)));
    if (!pass.completed) break;
  }
  stats.samples = accumulation_->sampleCount(0, 0);

  const embree::FrameBuffer& fb = *accumulation_;
  out = FrameBuffer(fb.width(), fb.height());
  out.colour = fb.colourImage();
  out.depth = fb.depthImage();
  // Named outputs are filled only where the caller reads them: all five
  // cost about a tenth of a 16-spp pass at 512x512.
  auto fill = [&](const char* name, auto read) {
    if (!control.wants(name)) return;
    auto& pixels = out.outputs[name];
    pixels.resize(out.colour.size());
    for (std::uint32_t y = 0; y < fb.height(); ++y)
      for (std::uint32_t x = 0; x < fb.width(); ++x) pixels[out.index(x, y)] = glm::vec4(read(x, y), 1.0f);
  };
  fill(kAlbedo, [&](std::uint32_t x, std::uint32_t y) { return fb.albedo(x, y); });
  fill(kNormal, [&](std::uint32_t x, std::uint32_t y) { return fb.normal(x, y); });
  fill(kDirect, [&](std::uint32_t x, std::uint32_t y) { return fb.mean(embree::Channel::Direct, x, y); });
  fill(kIndirect, [&](std::uint32_t x, std::uint32_t y) { return fb.mean(embree::Channel::Indirect, x, y); });
  fill(kVariance, [&](std::uint32_t x, std::uint32_t y) { return fb.variance(embree::Channel::Colour, x, y); });
  if (filter.usesPixelFilter() && stats.samples > 0) filterPixels(scene, camera, region, filter, spp, out, control);
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace tsr::med::embree_mediator
