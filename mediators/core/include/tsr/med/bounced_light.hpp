#pragma once
// Light bounced off the scene, computed by a back-end that traces rays for
// viewports whose back-end cannot (the rasterizer reads it instead of a
// constant ambient term). A back-end that can offers it through the
// registry (ViewportRegistry::addBouncedLight); one is shared by every
// viewport of a process on the same root and background (ContextPool).
// Every node computes its own from its replica: the same scene gives the
// same volume on every node, nothing goes over the wire.
#include <cstddef>
#include <cstdint>
#include <memory>

#include "tsr/backend/irradiance_volume.hpp"
#include "tsr/sg/replica.hpp"

namespace tsr::med {

struct BouncedLightState {
  std::shared_ptr<const backend::IrradianceVolume> volume;  // null: the scene is empty
  std::size_t staleProbes = 0;  // probes still showing the scene as it was before its last change
  std::uint64_t rays = 0;       // rays this update cast
};

class BouncedLight {
 public:
  virtual ~BouncedLight() = default;
  // Catches up with the replica and traces again up to `probes` of the
  // probes the scene changed under; 0: all of them. Every probe is traced
  // on the first update and when the scene grew out of the volume's box,
  // whatever `probes` says. Thread-safe.
  virtual BouncedLightState update(const sg::Replica& replica, std::uint32_t probes) = 0;
};

}  // namespace tsr::med
