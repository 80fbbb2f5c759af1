#pragma once
// The whole-image denoiser (filter=denoise, tsr/embree/denoiser.hpp) on a
// viewport's frame. Its guides travel as named outputs beside the colour,
// so the same resolve runs on a whole local frame and on a frame a cluster
// client assembled from tiles: both give one image.
#include <optional>
#include <string>
#include <vector>

#include "tsr/embree/denoiser.hpp"
#include "tsr/embree/framebuffer.hpp"
#include "tsr/med/frame_buffer.hpp"

namespace tsr::med::embree_mediator {

inline constexpr const char* kDenoiseAlbedoOutput = "denoise.albedo";      // rgb: first surface's albedo
inline constexpr const char* kDenoiseNormalOutput = "denoise.normal";      // rgb: its normal, a: its depth
inline constexpr const char* kDenoiseVarianceOutput = "denoise.variance";  // rgb: variance of the mean, a: samples
inline constexpr const char* kDenoiseHalfOutput = "denoise.half";  // rgb: first half's mean, a: its share of samples
inline constexpr const char* kDenoiseEmittedOutput = "denoise.emitted";  // rgb: emission seen from the camera

std::vector<std::string> denoiseInputs();

// Writes the denoiser's guides from the accumulated samples into `out`.
void writeDenoiseInputs(const embree::FrameBuffer& fb, FrameBuffer& out);

// Denoises frames from their guides; keeps the last denoised image, so a
// frame between two denoising passes shows it instead of raw samples. The
// kept image belongs to one accumulation (embree::FrameBuffer::epoch): when
// the path tracer restarts it, the image is no longer offered.
class DenoiseResolver {
 public:
  // Replaces frame's colour with the denoised image: computed anew when
  // `refresh`, or when nothing of accumulation `epoch` was denoised yet at
  // this size with these settings; else the kept one.
  void resolve(FrameBuffer& frame, const embree::DenoiseSettings& settings, bool refresh, std::uint64_t epoch);
  // The sample count the kept image of accumulation `epoch` was denoised at.
  std::optional<std::uint32_t> denoisedAt(std::uint64_t epoch) const;

 private:
  struct Kept {
    std::uint32_t width = 0, height = 0, samples = 0;
    std::uint64_t epoch = 0;
    embree::DenoiseSettings settings;
    std::vector<glm::vec3> image;
  };
  std::optional<Kept> last_;
};

}  // namespace tsr::med::embree_mediator
