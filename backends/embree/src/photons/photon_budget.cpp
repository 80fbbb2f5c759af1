#include "tsr/embree/photon_budget.hpp"

#include "tsr/embree/error.hpp"
#include "tsr/embree/sampling.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <string>

namespace tsr::embree {

namespace {

std::vector<float> luminanceImage(const FrameBuffer& fb) {
  std::vector<float> out(std::size_t(fb.width()) * fb.height());
  for (std::uint32_t y = 0; y < fb.height(); ++y)
    for (std::uint32_t x = 0; x < fb.width(); ++x)
      out[std::size_t(y) * fb.width() + x] = luminance(glm::vec3(fb.colour(x, y)));
  return out;
}

}  // namespace

PhotonBudget choosePhotonsPerFrame(Scene& scene, Renderer& renderer, const Camera& camera, const Region& region,
                                   const PoseFunction& pose, std::int64_t keyFrame, std::int64_t frames,
                                   PhotonSettings settings, const PhotonBudgetSettings& budget) {
  if (!pose) throw Error("choosePhotonsPerFrame needs a pose function");
  if (frames <= 0 || keyFrame < 0 || keyFrame >= frames)
    throw Error("key frame " + std::to_string(keyFrame) + " is not in [0, " + std::to_string(frames) + ")");
  if (!(budget.threshold >= 0.0f && budget.threshold <= 1.0f)) throw Error("budget threshold must be in [0, 1]");
  budget.vdp.validate();
  const std::int64_t h = (std::int64_t(settings.tMax) - 1) / 2;
  const std::int64_t first = std::max<std::int64_t>(0, keyFrame - h), last = std::min(frames - 1, keyFrame + h);

  PhotonBudget result;
  for (std::uint32_t round = 0; round < std::max(1u, budget.maxRounds); ++round) {
    PhotonSequence seq(settings);
    for (std::int64_t f = first; f <= last; ++f) {
      pose(scene, f);
      seq.addFrame(scene, f);
    }
    pose(scene, keyFrame);
    FrameBuffer even(region.regionWidth(), region.regionHeight()), odd(region.regionWidth(), region.regionHeight());
    renderer.renderWithIrradiance(scene, camera, region, even, seq.reconstruct(keyFrame, PhotonHalf::Even).field);
    renderer.renderWithIrradiance(scene, camera, region, odd, seq.reconstruct(keyFrame, PhotonHalf::Odd).field);
    const VisibleDifference d =
        predictVisibleDifference(luminanceImage(even), luminanceImage(odd), even.width(), even.height(), budget.vdp);
    result.photonsPerFrame = seq.photonsPerFrame();
    result.fractionVisible = d.fractionVisible;
    result.rounds = round + 1;
    spdlog::debug("tsr::embree: {} photons per frame: {:.2f}% of pixels visibly noisy", result.photonsPerFrame,
                  100.0f * d.fractionVisible);
    if (d.fractionVisible <= budget.threshold) break;
    settings.photonsPerFrame = 2 * seq.photonsPerFrame();
  }
  return result;
}

}  // namespace tsr::embree
