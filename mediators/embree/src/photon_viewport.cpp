#include "photon_viewport.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

#include "embree_parameters.hpp"
#include "render_outputs.hpp"
#include "tsr/med/view_translation.hpp"

namespace tsr::med::embree_mediator {

namespace {
const ParameterTable& table() { return embreeParameters(); }

bool objectPca(const Parameters& p) { return table().choice(p, "temporal") == "objectPca"; }

int pcaWindow(const Parameters& p) { return static_cast<int>(table().integer(p, "pcaWindow")); }

temporal::WindowedPca pcaFrom(const Parameters& p) {
  temporal::PcaSettings s;
  s.rule.epsilon = table().real(p, "pcaEpsilon");
  s.rule.epsilonChange = table().real(p, "pcaEpsilonChange");
  s.rule.noiseAware = !table().flag(p, "pcaPlainRule");
  s.fixedModes = static_cast<int>(table().integer(p, "pcaModes"));
  s.perPixel = false;
  const int window = pcaWindow(p);
  try {
    const int overlap =
        p.has("pcaOverlap") ? static_cast<int>(table().integer(p, "pcaOverlap")) : std::min(16, window / 4);
    return temporal::WindowedPca(window, overlap, s);
  } catch (const std::invalid_argument& e) {
    throw ParameterError(e.what());
  }
}
}  // namespace

embree::PhotonSettings photonSettingsFrom(const Parameters& p) {
  embree::PhotonSettings s;
  s.photonsPerFrame = static_cast<std::uint32_t>(table().integer(p, "photonsPerFrame"));
  // Object-space PCA reads each frame's photons once, as they are traced.
  s.tMax = objectPca(p) ? 1 : static_cast<std::uint32_t>(table().integer(p, "photonFrames"));
  if (objectPca(p)) s.budgetFrames = static_cast<std::uint32_t>(pcaWindow(p));
  if (s.tMax % 2 == 0)
    throw ParameterError("photonFrames = " + std::to_string(s.tMax) +
                         ": the window is centred on the frame it reconstructs, so it must be odd");
  s.accuracy = static_cast<float>(table().real(p, "photonAccuracy"));
  s.maxError = static_cast<float>(table().real(p, "photonMaxError"));
  s.emissionStep = static_cast<float>(table().real(p, "photonEmissionStep"));
  s.maxBounces = static_cast<std::uint32_t>(table().integer(p, "maxDepth"));
  s.seed = static_cast<std::uint64_t>(table().integer(p, "seed"));
  s.threads = static_cast<int>(table().integer(p, "threads"));
  s.validate();  // an even window or a non-positive accuracy throws embree::Error naming it
  return s;
}

PhotonViewport::PhotonViewport(ViewportSettings settings, const std::shared_ptr<embree::Device>& device)
    : Viewport(std::move(settings)),
      ahead_(device, settings_.root, settings_.background),
      shown_(device, settings_.root, settings_.background),
      photons_(photonSettingsFrom(settings_.parameters)) {
  if (objectPca(settings_.parameters)) pca_.emplace(pcaFrom(settings_.parameters));
}

// A frame's element irradiance leaves the PCA at most a window minus one
// frames after it went in.
std::uint32_t PhotonViewport::lookahead() const {
  return pca_ ? static_cast<std::uint32_t>(pcaWindow(settings_.parameters) - 1) : photons_.lookahead();
}

void PhotonViewport::prepare(const sg::Replica& ahead, std::int64_t frame) {
  ahead_.catchUp(ahead);
  photons_.addFrame(ahead_.scene(), frame);
  if (!pca_) return;
  if (firstFrame_ < 0) firstFrame_ = frame;
  const std::vector<glm::vec3> raw = photons_.rawIrradiance(frame);
  // Per unit of emitted power, which is known exactly: a light switched or
  // dimmed as a whole is then no change for the projection to smooth over
  // (with few photons an element's noise outweighs such a step, and the
  // truncation would drop it), and keep() restores it exactly.
  const float power = photons_.emittedPower(frame);
  power_[frame] = power;
  const float scale = power > 0.0f ? 1.0f / power : 0.0f;
  temporal::Frame f(static_cast<std::uint32_t>(raw.size()), 1);
  for (std::size_t e = 0; e < raw.size(); ++e)
    for (int c = 0; c < 3; ++c) f.rgb[3 * e + std::size_t(c)] = raw[e][c] * scale;
  keep(pca_->push(std::move(f)));
}

void PhotonViewport::keep(std::vector<temporal::DenoisedFrame> denoised) {
  for (auto& d : denoised) {
    const std::int64_t frame = firstFrame_ + d.index;
    const auto power = power_.find(frame);
    std::vector<glm::vec3> values(d.frame.pixels());
    // A projection can dip under zero where the noise was; irradiance cannot.
    for (std::size_t e = 0; e < values.size(); ++e)
      values[e] =
          power->second * glm::max(glm::vec3(d.frame.rgb[3 * e], d.frame.rgb[3 * e + 1], d.frame.rgb[3 * e + 2]), 0.0f);
    power_.erase(power);
    denoised_[frame] = std::move(values);
  }
}

const embree::IrradianceField& PhotonViewport::field(std::int64_t frame) {
  // A frame may be rendered in several parts (a cluster node's tiles): its
  // field is made once.
  if (shownField_ && shownField_->first == frame) return shownField_->second;
  if (!pca_) {
    shownField_.emplace(frame, photons_.reconstruct(frame).field);  // throws embree::Error for a frame not buffered
    return shownField_->second;
  }
  // Not denoised yet, a lookahead after it was prepared: the sequence ended.
  if (!denoised_.count(frame)) keep(pca_->finish());
  auto it = denoised_.find(frame);
  if (it == denoised_.end())
    throw std::invalid_argument("temporal = objectPca: frame " + std::to_string(frame) + " was not prepared");
  shownField_.emplace(frame, photons_.field(std::move(it->second)));
  denoised_.erase(denoised_.begin(), std::next(it));  // frames are shown in order
  return shownField_->second;
}

SceneAdapter::Update PhotonViewport::synchronize(const sg::Replica& replica) { return shown_.catchUp(replica); }

std::vector<std::string> PhotonViewport::outputNames() const { return accumulatedOutputNames(); }

RenderStats PhotonViewport::render(const sg::Replica& replica, const View& view, FrameBuffer& out,
                                   const RenderControl& control) {
  view.validate();
  if (control.frame < 0)
    throw std::invalid_argument("temporal = " + table().choice(settings_.parameters, "temporal") +
                                " renders frames of an animation: RenderControl::frame is not set");
  const auto start = std::chrono::steady_clock::now();
  const auto spp = static_cast<std::uint32_t>(table().integer(settings_.parameters, "spp"));
  RenderStats stats;
  stats.update = shown_.catchUp(replica);
  embree::Scene& scene = shown_.scene();
  scene.commit();
  stats.syncSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const embree::IrradianceField& field = this->field(control.frame);

  const embree::Camera camera = cameraOf(view);
  const embree::Region region = regionOf(view);
  embree::FrameBuffer fb(region.regionWidth(), region.regionHeight());
  embree::RenderSettings settings = renderSettingsFrom(settings_.parameters, control.frame);
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
