#include "photon_viewport.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

#include "render_outputs.hpp"

namespace tsr::med::embree_mediator {

embree::PhotonSettings photonSettingsFrom(const Parameters& p) {
  embree::PhotonSettings s;
  s.photonsPerFrame = static_cast<std::uint32_t>(p.getInt("photonsPerFrame", 0, 0, 1 << 30));
  s.tMax = static_cast<std::uint32_t>(p.getInt("photonFrames", 9, 1, 255));
  if (s.tMax % 2 == 0)
    throw ParameterError("photonFrames = " + std::to_string(s.tMax) +
                         ": the window is centred on the frame it reconstructs, so it must be odd");
  s.accuracy = static_cast<float>(p.getReal("photonAccuracy", s.accuracy));
  s.maxError = static_cast<float>(p.getReal("photonMaxError", s.maxError));
  s.emissionStep = static_cast<float>(p.getReal("photonEmissionStep", s.emissionStep));
  s.maxBounces = static_cast<std::uint32_t>(p.getInt("maxDepth", 8, 0, 1024));
  s.seed = static_cast<std::uint64_t>(p.getInt("seed", 0, 0));
  s.threads = static_cast<int>(p.getInt("threads", 0, 0, 4096));
  s.validate();  // an even window or a non-positive accuracy throws embree::Error naming it
  return s;
}

PhotonViewport::PhotonViewport(ViewportSettings settings, const std::shared_ptr<embree::Device>& device)
    : Viewport(std::move(settings)),
      ahead_(device, settings_.root, settings_.background),
      shown_(device, settings_.root, settings_.background),
      photons_(photonSettingsFrom(settings_.parameters)) {}

void PhotonViewport::prepare(const sg::Replica& ahead, std::int64_t frame) {
  ahead_.catchUp(ahead);
  photons_.addFrame(ahead_.scene(), frame);
}

SceneAdapter::Update PhotonViewport::synchronize(const sg::Replica& replica) { return shown_.catchUp(replica); }

std::vector<std::string> PhotonViewport::outputNames() const { return accumulatedOutputNames(); }

RenderStats PhotonViewport::render(const sg::Replica& replica, const View& view, FrameBuffer& out,
                                   const RenderControl& control) {
  view.validate();
  if (control.frame < 0)
    throw std::invalid_argument("temporal = photons renders frames of an animation: RenderControl::frame is not set");
  const auto start = std::chrono::steady_clock::now();
  const auto spp = static_cast<std::uint32_t>(settings_.parameters.getInt("spp", 16, 1, 1 << 20));
  RenderStats stats;
  stats.update = shown_.catchUp(replica);
  embree::Scene& scene = shown_.scene();
  scene.commit();
  stats.syncSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Throws embree::Error for a frame that was not prepared or left the window.
  const embree::IrradianceField field = photons_.reconstruct(control.frame).field;

  const embree::Camera camera = cameraOf(view);
  const embree::Region region = regionOf(view);
  embree::FrameBuffer fb(region.regionWidth(), region.regionHeight());
  embree::RenderSettings settings = renderSettingsFrom(settings_.parameters);
  // Passes of up to 8 samples, so progress shows and a cancel is heard.
  for (std::uint32_t done = 0; done < spp;) {
    if (control.cancel && control.cancel->load()) break;
    settings.samplesPerPass = std::min(8u, spp - done);
    renderer_.setSettings(settings);
    const auto pass = renderer_.renderWithIrradiance(scene, camera, region, fb, field);
    stats.rays += pass.rays;
    done = fb.sampleCount(0, 0);
    if (control.progress) control.progress(std::min(1.0, done / double(spp)));
    if (!pass.completed) break;
  }
  stats.samples = fb.sampleCount(0, 0);
  out = accumulatedFrame(fb, control);
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace tsr::med::embree_mediator
