#include "denoising.hpp"

#include "required_output.hpp"

#include <algorithm>

namespace tsr::med::embree_mediator {

std::vector<std::string> denoiseInputs() {
  return {kDenoiseAlbedoOutput, kDenoiseNormalOutput, kDenoiseVarianceOutput, kDenoiseHalfOutput,
          kDenoiseEmittedOutput};
}

void writeDenoiseInputs(const embree::FrameBuffer& fb, FrameBuffer& out) {
  const std::size_t n = std::size_t{fb.width()} * fb.height();
  const auto [albedo, normal, variance, half, emitted] = zeroedOutputs(
      out,
      {kDenoiseAlbedoOutput, kDenoiseNormalOutput, kDenoiseVarianceOutput, kDenoiseHalfOutput, kDenoiseEmittedOutput},
      n);
  for (std::uint32_t y = 0; y < fb.height(); ++y)
    for (std::uint32_t x = 0; x < fb.width(); ++x) {
      const std::size_t i = out.index(x, y);
      const std::uint32_t count = fb.sampleCount(x, y);
      (*albedo)[i] = glm::vec4(fb.albedo(x, y), 0.0f);
      (*normal)[i] = glm::vec4(fb.normal(x, y), fb.depth(x, y));
      const glm::vec3 v = count > 0 ? fb.variance(embree::Channel::Colour, x, y) / float(count) : glm::vec3(0.0f);
      (*variance)[i] = glm::vec4(v, float(count));
      const std::uint32_t first = fb.firstHalfCount(x, y);
      (*half)[i] = glm::vec4(fb.firstHalf(x, y), count > 0 ? float(first) / float(count) : 0.0f);
      (*emitted)[i] = glm::vec4(fb.emitted(x, y), 0.0f);
    }
}

std::optional<std::uint32_t> DenoiseResolver::denoisedAt(std::uint64_t epoch) const {
  if (!last_ || last_->epoch != epoch) return std::nullopt;
  return last_->samples;
}

void DenoiseResolver::resolve(FrameBuffer& frame, const embree::DenoiseSettings& settings, bool refresh,
                              std::uint64_t epoch) {
  const std::size_t n = frame.colour.size();
  const auto& albedo = requiredOutput(frame, kDenoiseAlbedoOutput, "denoising");
  const auto& normal = requiredOutput(frame, kDenoiseNormalOutput, "denoising");      // depth in alpha
  const auto& variance = requiredOutput(frame, kDenoiseVarianceOutput, "denoising");  // samples in alpha
  const auto& half = requiredOutput(frame, kDenoiseHalfOutput, "denoising");          // its share in alpha
  const auto& emitted = requiredOutput(frame, kDenoiseEmittedOutput, "denoising");
  const bool stale = !last_ || last_->epoch != epoch || last_->width != frame.width || last_->height != frame.height ||
                     last_->settings != settings;
  if (refresh || stale) {
    std::uint32_t samples = 0;
    for (const glm::vec4& v : variance) samples = std::max(samples, static_cast<std::uint32_t>(v.a));
    const auto colourRgb = rgbOf(frame.colour), albedoRgb = rgbOf(albedo), normalRgb = rgbOf(normal),
               varianceRgb = rgbOf(variance), halfRgb = rgbOf(half), emittedRgb = rgbOf(emitted);
    const auto depth = channelOf(normal, 3), share = channelOf(half, 3);
    const embree::DenoiseInput input{.width = frame.width,
                                     .height = frame.height,
                                     .colour = colourRgb,
                                     .variance = varianceRgb,
                                     .albedo = albedoRgb,
                                     .normal = normalRgb,
                                     .depth = depth,
                                     .firstHalf = halfRgb,
                                     .firstHalfShare = share,
                                     .emitted = emittedRgb};
    last_ = Kept{frame.width, frame.height, samples, epoch, settings, embree::denoise(input, settings)};
  }
  for (std::size_t i = 0; i < n; ++i) frame.colour[i] = glm::vec4(last_->image[i], frame.colour[i].a);
}

}  // namespace tsr::med::embree_mediator
