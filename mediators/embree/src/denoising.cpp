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
  auto& albedo = out.outputs[kDenoiseAlbedoOutput];
  auto& normal = out.outputs[kDenoiseNormalOutput];
  auto& variance = out.outputs[kDenoiseVarianceOutput];
  auto& half = out.outputs[kDenoiseHalfOutput];
  auto& emitted = out.outputs[kDenoiseEmittedOutput];
  for (auto* image : {&albedo, &normal, &variance, &half, &emitted}) image->assign(n, glm::vec4(0.0f));
  for (std::uint32_t y = 0; y < fb.height(); ++y)
    for (std::uint32_t x = 0; x < fb.width(); ++x) {
      const std::size_t i = out.index(x, y);
      const std::uint32_t count = fb.sampleCount(x, y);
      albedo[i] = glm::vec4(fb.albedo(x, y), 0.0f);
      normal[i] = glm::vec4(fb.normal(x, y), fb.depth(x, y));
      const glm::vec3 v = count > 0 ? fb.variance(embree::Channel::Colour, x, y) / float(count) : glm::vec3(0.0f);
      variance[i] = glm::vec4(v, float(count));
      const std::uint32_t first = fb.firstHalfCount(x, y);
      half[i] = glm::vec4(fb.firstHalf(x, y), count > 0 ? float(first) / float(count) : 0.0f);
      emitted[i] = glm::vec4(fb.emitted(x, y), 0.0f);
    }
}

std::optional<std::uint32_t> DenoiseResolver::denoisedAt(std::uint64_t epoch) const {
  if (!last_ || last_->epoch != epoch) return std::nullopt;
  return last_->samples;
}

void DenoiseResolver::resolve(FrameBuffer& frame, const embree::DenoiseSettings& settings, bool refresh,
                              std::uint64_t epoch) {
  const std::size_t n = frame.colour.size();
  const char* names[5] = {kDenoiseAlbedoOutput, kDenoiseNormalOutput, kDenoiseVarianceOutput, kDenoiseHalfOutput,
                          kDenoiseEmittedOutput};
  const std::vector<glm::vec4>* images[5] = {};
  for (int k = 0; k < 5; ++k) images[k] = &requiredOutput(frame, names[k], "denoising");
  const bool stale = !last_ || last_->epoch != epoch || last_->width != frame.width || last_->height != frame.height ||
                     last_->settings != settings;
  if (refresh || stale) {
    std::vector<glm::vec3> colour(n), albedo(n), normal(n), variance(n), half(n), emitted(n);
    std::vector<float> depth(n), share(n);
    std::uint32_t samples = 0;
    for (std::size_t i = 0; i < n; ++i) {
      colour[i] = glm::vec3(frame.colour[i]);
      albedo[i] = glm::vec3((*images[0])[i]);
      normal[i] = glm::vec3((*images[1])[i]);
      depth[i] = (*images[1])[i].a;
      variance[i] = glm::vec3((*images[2])[i]);
      half[i] = glm::vec3((*images[3])[i]);
      share[i] = (*images[3])[i].a;
      emitted[i] = glm::vec3((*images[4])[i]);
      samples = std::max(samples, static_cast<std::uint32_t>((*images[2])[i].a));
    }
    embree::DenoiseInput input;
    input.width = frame.width;
    input.height = frame.height;
    input.colour = colour;
    input.variance = variance;
    input.albedo = albedo;
    input.normal = normal;
    input.depth = depth;
    input.firstHalf = half;
    input.firstHalfShare = share;
    input.emitted = emitted;
    last_ = Kept{frame.width, frame.height, samples, epoch, settings, embree::denoise(input, settings)};
  }
  for (std::size_t i = 0; i < n; ++i) frame.colour[i] = glm::vec4(last_->image[i], frame.colour[i].a);
}

}  // namespace tsr::med::embree_mediator
