#pragma once
// The path tracer's bounced light for other viewports (tsr/med/bounced_light.hpp):
// an irradiance volume over the scene the Embree viewports on the same
// root and background convert (one shared EmbreeContext), its probes
// traced by embree::traceProbes, kPaths paths each. The first update
// traces every probe; after an edit each is traced anew, `probes` an
// update (the volume mixing old and new probes meanwhile) or all at once.
// A probe's values depend on the scene alone, not on the turns it was
// traced in.
#include <mutex>

#include "embree_viewport.hpp"
#include "tsr/embree/probe_tracing.hpp"
#include "tsr/med/bounced_light.hpp"

namespace tsr::med::embree_mediator {

class ProbeLight final : public BouncedLight {
 public:
  static constexpr std::uint32_t kMaxProbes = 512;
  static constexpr std::uint32_t kPaths = 512;

  explicit ProbeLight(std::shared_ptr<EmbreeContext> context) : context_(std::move(context)) {}
  BouncedLightState update(const sg::Replica& replica, std::uint32_t probes) override;

 private:
  // Whether the box [lo, hi] no longer fits the volume (a part left it) or
  // fills less than half of it along an axis.
  bool outgrown(const glm::vec3& lo, const glm::vec3& hi) const;

  std::shared_ptr<EmbreeContext> context_;
  std::mutex mutex_;  // one update at a time
  backend::IrradianceVolume working_;
  std::vector<embree::ProbeSums> sums_;
  std::shared_ptr<const backend::IrradianceVolume> published_;
  glm::vec3 boundsLo_{0.0f}, boundsHi_{0.0f};  // the scene's box the volume was laid out for
  std::uint64_t sceneVersion_ = 0;             // what the probes are being brought up to
  std::size_t next_ = 0;                       // the probe traced next
  std::size_t stale_ = 0;                      // probes not yet traced since sceneVersion_
};

}  // namespace tsr::med::embree_mediator
