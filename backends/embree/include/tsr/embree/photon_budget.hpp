#pragma once

#include "tsr/embree/photon_sequence.hpp"
#include "tsr/embree/renderer.hpp"
#include "tsr/embree/visible_difference.hpp"

#include <cstdint>
#include <functional>

namespace tsr::embree {

// The perceptual stopping rule of Myszkowski et al. 2001 §5.2.3: the
// photons of the frames around a key frame are split into even and odd
// halves, the key frame is rendered with each half's reconstruction (same
// camera samples, so only the indirect light differs), and N_frame doubles
// while predictVisibleDifference finds more than `threshold` of the pixels
// above one JND. Halving is conservative: all photons are sqrt(2) less noisy.
struct PhotonBudgetSettings {
  float threshold = 0.02f;      // d_thr: fraction of pixels allowed above 1 JND
  std::uint32_t maxRounds = 6;  // doublings at most
  VisibleDifferenceSettings vdp;
};

struct PhotonBudget {
  std::uint32_t photonsPerFrame = 0;  // the chosen N_frame
  float fractionVisible = 0.0f;       // d at that N_frame
  std::uint32_t rounds = 0;           // reconstructions compared
};

// Poses the scene (instances, lights) as at `frame`; the caller's animation.
using PoseFunction = std::function<void(Scene& scene, std::int64_t frame)>;

// Starts from settings.photonsPerFrame, or from the pilot pass's N_frame
// (eq. 3) when that is 0. Frames of the sequence are [0, frames); the
// renderer's settings (samplesPerPass, seed) are used for both renders.
// Leaves the scene posed at keyFrame.
PhotonBudget choosePhotonsPerFrame(Scene& scene, Renderer& renderer, const Camera& camera, const Region& region,
                                   const PoseFunction& pose, std::int64_t keyFrame, std::int64_t frames,
                                   PhotonSettings settings, const PhotonBudgetSettings& budget = {});

}  // namespace tsr::embree
