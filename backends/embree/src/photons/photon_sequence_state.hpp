#pragma once
// PhotonSequence's state: the elements and the ring buffer of per-frame
// counters (Weber et al. 2004 §4). Private.
#include "photons/photon_elements.hpp"
#include "tsr/embree/error.hpp"
#include "tsr/embree/photon_sequence.hpp"

#include <oneapi/tbb/task_arena.h>

#include <memory>
#include <string>
#include <vector>

namespace tsr::embree {

struct PhotonSequence::State {
  struct Slot {
    std::int64_t frame = 0;
    bool used = false;
    std::vector<std::uint32_t> count;    // 2 per element: even and odd photons
    std::vector<glm::vec3> energy;       // 2 per element
    ElementGeometry geometry;            // element centroids, normals, areas at this frame's pose
    std::vector<glm::vec3> sourcePower;  // per light and emissive triangle, in the scene's order
  };

  PhotonSettings settings;
  std::unique_ptr<tbb::task_arena> arena;
  std::shared_ptr<const ElementSet> elements;
  std::uint64_t sceneUid = 0;
  std::uint32_t photonsPerFrame = 0;
  float pilotError = 0.0f;
  float photonEnergy = 0.0f;  // luminance of one photon's power, fixed at the first frame
  bool started = false;
  std::int64_t last = 0;
  std::vector<Slot> ring;  // tMax slots, frame f in slot f mod tMax

  const Slot* slot(std::int64_t frame) const {
    const Slot& s = ring[std::size_t(((frame % std::int64_t(ring.size())) + std::int64_t(ring.size())) %
                                     std::int64_t(ring.size()))];
    return s.used && s.frame == frame ? &s : nullptr;
  }
  const Slot& buffered(std::int64_t frame) const {
    const Slot* s = started ? slot(frame) : nullptr;
    if (!s)
      throw Error("photon frame " + std::to_string(frame) + " is not buffered (the last " +
                  std::to_string(ring.size()) + " added frames are)");
    return *s;
  }
};

}  // namespace tsr::embree
