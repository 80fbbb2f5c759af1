#include "probe_light.hpp"

#include <glm/common.hpp>

namespace tsr::med::embree_mediator {

bool ProbeLight::outgrown(const glm::vec3& lo, const glm::vec3& hi) const {
  if (working_.empty()) return true;
  const glm::vec3 held = boundsHi_ - boundsLo_, now = hi - lo;
  for (int a = 0; a < 3; ++a)
    if (lo[a] < working_.min[a] || hi[a] > working_.max[a] || now[a] < 0.5f * held[a]) return true;
  return false;
}

BouncedLightState ProbeLight::update(const sg::Replica& replica, std::uint32_t probes) {
  std::lock_guard own(mutex_);
  std::lock_guard lock(context_->mutex);
  context_->adapter.catchUp(replica);
  embree::Scene& scene = context_->adapter.scene();
  scene.commit();
  BouncedLightState state;
  glm::vec3 lo, hi;
  if (!scene.bounds(lo, hi)) {
    working_ = {};
    sums_.clear();
    published_.reset();
    return state;
  }
  std::size_t count = probes == 0 ? working_.probeCount() : probes;
  if (outgrown(lo, hi)) {
    const std::uint64_t version = working_.version;
    working_ = backend::IrradianceVolume::over(lo, hi, kMaxProbes);
    working_.version = version + 1;
    sums_.assign(working_.probeCount(), {});
    boundsLo_ = lo;
    boundsHi_ = hi;
    sceneVersion_ = scene.version();
    next_ = 0;
    stale_ = working_.probeCount();
    count = stale_;  // a new layout has no old values to show meanwhile
  } else if (scene.version() != sceneVersion_) {
    sceneVersion_ = scene.version();
    stale_ = working_.probeCount();
  }
  const std::size_t n = working_.probeCount();
  count = std::min(count, stale_);
  if (count > 0) {
    for (std::size_t i = 0; i < count; ++i) sums_[(next_ + i) % n] = {};
    stale_ -= count;
    state.rays = embree::traceProbes(scene, embree::RenderSettings{}, working_, sums_, next_, count, kPaths);
    next_ = (next_ + count) % n;
    published_ = std::make_shared<const backend::IrradianceVolume>(working_);
  }
  state.volume = published_;
  state.staleProbes = stale_;
  return state;
}

}  // namespace tsr::med::embree_mediator
