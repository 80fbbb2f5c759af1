#include "photons/photon_pass.hpp"
#include "photons/photon_sequence_state.hpp"
#include "tsr/embree/error.hpp"
#include "tsr/embree/rng.hpp"
#include "tsr/embree/sampling.hpp"

#include <spdlog/spdlog.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <string>

namespace tsr::embree {

namespace {

constexpr std::uint64_t kFrameStream = 0x50484F544F4E5331ull;  // photons of a frame
constexpr std::uint64_t kPilotStream = 0x50494C4F54504153ull;  // the pilot pass
constexpr float kMaxBrightening = 64.0f;                       // photons per frame at most this times N_frame

float sceneDiagonal(const SceneState& scene) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const InstanceView& v : scene.views) {
    if (!v.mesh) continue;
    for (const glm::vec3& p : v.mesh->positions) {
      const glm::vec3 w(v.transform * glm::vec4(p, 1.0f));
      lo = glm::min(lo, w), hi = glm::max(hi, w);
    }
  }
  return hi.x >= lo.x ? glm::length(hi - lo) : 0.0f;
}

// Energy-weighted mean relative error of the element estimates, 1/sqrt(n)
// per element (Weber eq. 4): the global accuracy E of a pass.
float passError(const std::vector<PhotonHit>& hits, std::size_t elements) {
  std::vector<std::uint32_t> n(elements, 0);
  std::vector<float> energy(elements, 0.0f);
  for (const PhotonHit& h : hits) ++n[h.element], energy[h.element] += luminance(h.power);
  double num = 0.0, den = 0.0;
  for (std::size_t e = 0; e < elements; ++e) {
    if (n[e] == 0) continue;
    num += energy[e] / std::sqrt(double(n[e]));
    den += energy[e];
  }
  return den > 0.0 ? float(num / den) : 1.0f;
}

}  // namespace

void PhotonSettings::validate() const {
  if (!(elementSize >= 0.0f) || !std::isfinite(elementSize)) throw Error("photon elementSize must be finite and >= 0");
  if (maxElements == 0) throw Error("photon maxElements must be at least 1");
  if (tMax == 0 || tMax > 255) throw Error("photon tMax must be in [1, 255], got " + std::to_string(tMax));
  if (photonsPerFrame == 0 && pilotPhotons == 0)
    throw Error("photon pilotPhotons must be >= 1 without photonsPerFrame");
  if (!(maxError > 0.0f) || !(accuracy > 0.0f) || !(influence > 0.0f) || !(validityK > 0.0f))
    throw Error("photon maxError, accuracy, influence and validityK must be > 0");
  if (!(emissionStep >= 0.0f) || !std::isfinite(emissionStep))
    throw Error("photon emissionStep must be a finite relative change >= 0");
  if (!(creaseAngle >= 0.0f && creaseAngle <= kPi)) throw Error("photon creaseAngle must be in [0, pi]");
  if (maxRings > 64) throw Error("photon maxRings must be at most 64");
  if (threads < 0) throw Error("photon threads must be >= 0 (0 = all)");
}

PhotonSequence::PhotonSequence(PhotonSettings settings) : s_(std::make_unique<State>()) {
  settings.validate();
  s_->settings = settings;
  s_->arena =
      std::make_unique<tbb::task_arena>(settings.threads > 0 ? settings.threads : int(tbb::task_arena::automatic));
  s_->ring.resize(settings.tMax);
}
PhotonSequence::~PhotonSequence() = default;
PhotonSequence::PhotonSequence(PhotonSequence&&) noexcept = default;
PhotonSequence& PhotonSequence::operator=(PhotonSequence&&) noexcept = default;

std::uint32_t PhotonSequence::lookahead() const { return (s_->settings.tMax - 1) / 2; }
std::uint32_t PhotonSequence::photonsPerFrame() const { return s_->photonsPerFrame; }
float PhotonSequence::pilotError() const { return s_->pilotError; }
std::size_t PhotonSequence::elementCount() const { return s_->elements ? s_->elements->elementCount() : 0; }
const PhotonSettings& PhotonSequence::settings() const { return s_->settings; }

std::vector<glm::vec3> PhotonSequence::rawIrradiance(std::int64_t frame) const {
  const State::Slot* slot = &s_->buffered(frame);
  std::vector<glm::vec3> out(slot->geometry.area.size(), glm::vec3(0.0f));
  for (std::size_t e = 0; e < out.size(); ++e)
    if (slot->geometry.area[e] > 0.0f)
      out[e] = (slot->energy[2 * e] + slot->energy[2 * e + 1]) / slot->geometry.area[e];
  return out;
}

float PhotonSequence::emittedPower(std::int64_t frame) const {
  float power = 0.0f;
  for (const glm::vec3& p : s_->buffered(frame).sourcePower) power += luminance(p);
  return power;
}

FrameStats PhotonSequence::addFrame(Scene& scene, std::int64_t frame) {
  State& s = *s_;
  const PhotonSettings& cfg = s.settings;
  if (s.started && frame != s.last + 1)
    throw Error("photon frames must be consecutive: got " + std::to_string(frame) + " after " + std::to_string(s.last));
  scene.commit();
  const SceneState& state = scene.state();
  if (!s.started) {
    const float size = cfg.elementSize > 0.0f ? cfg.elementSize : sceneDiagonal(state) / 40.0f;
    s.elements = std::make_shared<const ElementSet>(buildElements(state, size, cfg.maxElements));
    s.sceneUid = scene.uid();
  } else if (scene.uid() != s.sceneUid || !s.elements->matches(state)) {
    throw Error("the scene's instances or mesh topology changed during a photon sequence (frame " +
                std::to_string(frame) + "); start a new PhotonSequence");
  }
  const ElementSet& elements = *s.elements;
  ElementGeometry geometry = elementGeometry(elements, state);
  std::vector<glm::vec3> sourcePower = sourcePowers(state, geometry);
  float power = 0.0f;
  for (const glm::vec3& p : sourcePower) power += luminance(p);

  FrameStats stats;
  if (!s.started) {
    s.photonsPerFrame = cfg.photonsPerFrame;
    if (s.photonsPerFrame == 0) {
      // Weber eq. 3: N_frame = E_pilot^2 / E_max^2 * N_pilot / t_max (the
      // frames whose photons one estimate combines).
      PhotonPassResult pilot =
          tracePhotons(state, elements, geometry, cfg.pilotPhotons,
                       Rng::pixelKey(cfg.seed ^ kPilotStream, std::uint32_t(frame), 0), cfg.maxBounces, *s.arena);
      stats.rays += pilot.rays;
      s.pilotError = passError(pilot.hits, elements.elementCount());
      const double n = double(s.pilotError) * s.pilotError / (double(cfg.maxError) * cfg.maxError) *
                       double(cfg.pilotPhotons) / double(cfg.budgetFrames ? cfg.budgetFrames : cfg.tMax);
      s.photonsPerFrame = std::uint32_t(std::clamp(std::ceil(n), 256.0, double(1u << 24)));
      spdlog::debug("tsr::embree: photon pilot E = {:.3f} over {} elements -> {} photons per frame", s.pilotError,
                    elements.elementCount(), s.photonsPerFrame);
    }
    s.photonEnergy = power > 0.0f ? power / float(s.photonsPerFrame) : 0.0f;
    s.started = true;
  }
  s.last = frame;

  // Photons of fixed energy: a frame's count follows its emitted power.
  std::uint64_t photons = 0;
  if (s.photonEnergy > 0.0f && power > 0.0f)
    photons =
        std::uint64_t(std::min(double(power) / s.photonEnergy, double(kMaxBrightening) * s.photonsPerFrame) + 0.5);
  PhotonPassResult pass =
      tracePhotons(state, elements, geometry, photons, Rng::pixelKey(cfg.seed ^ kFrameStream, std::uint32_t(frame), 1),
                   cfg.maxBounces, *s.arena);

  const std::size_t size = s.ring.size();
  State::Slot& slot = s.ring[std::size_t(((frame % std::int64_t(size)) + std::int64_t(size)) % std::int64_t(size))];
  slot.frame = frame;
  slot.used = true;
  slot.count.assign(2 * elements.elementCount(), 0);
  slot.energy.assign(2 * elements.elementCount(), glm::vec3(0.0f));
  for (const PhotonHit& h : pass.hits) {
    ++slot.count[2 * std::size_t(h.element) + h.parity];
    slot.energy[2 * std::size_t(h.element) + h.parity] += h.power;
  }
  slot.geometry = std::move(geometry);
  slot.sourcePower = std::move(sourcePower);
  stats.photons = photons;
  stats.hits = pass.hits.size();
  stats.rays += pass.rays;
  return stats;
}

}  // namespace tsr::embree
