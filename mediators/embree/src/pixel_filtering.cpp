#include "pixel_filtering.hpp"

#include "required_output.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tsr::med::embree_mediator {

std::vector<std::string> pixelFilterInputs() {
  return {kLowVarianceOutput, kHighVarianceOutput, kHighVarianceVarOutput, kRangeOutput, kRangeGeometryOutput};
}

std::uint32_t flashSamplesFor(std::uint32_t samples) {
  std::uint32_t passes = 1;
  for (std::uint32_t n = 8; n <= samples && n != 0; n *= 2) ++passes;
  return 4 * passes;
}

void writePixelFilterInputs(const embree::FrameBuffer& fb, PathClass pathClass, FrameBuffer& out,
                            const embree::RadianceAccumulator* hybrid) {
  const std::size_t n = std::size_t{fb.width()} * fb.height();
  const auto [low, high, var, range, spread] = zeroedOutputs(
      out, {kLowVarianceOutput, kHighVarianceOutput, kHighVarianceVarOutput, kRangeOutput, kRangeGeometryOutput}, n);
  const embree::Channel hv = pathClass == PathClass::Indirect  ? embree::Channel::Indirect
                             : pathClass == PathClass::Caustic ? embree::Channel::Caustic
                                                               : embree::Channel::Colour;
  for (std::uint32_t y = 0; y < fb.height(); ++y)
    for (std::uint32_t x = 0; x < fb.width(); ++x) {
      const std::size_t i = out.index(x, y);
      const std::uint32_t count = fb.sampleCount(x, y);
      // Hybrid (4.6.1): pixels seen through glass get all their indirect
      // light pixel-filtered; elsewhere radiance filtering took the rest
      // and only the caustics are left, which it leaves unfiltered.
      const embree::Channel c = !hybrid                                              ? hv
                                : (hybrid->mask(x, y) & embree::kMaskReflectRefract) ? embree::Channel::Indirect
                                                                                     : embree::Channel::Caustic;
      const glm::vec3 h = fb.mean(c, x, y);
      const glm::vec3 shown = hybrid ? glm::vec3(out.colour[i]) : fb.mean(embree::Channel::Colour, x, y);
      (*high)[i] = glm::vec4(h, 0.0f);
      (*low)[i] = glm::vec4(shown - h, 0.0f);
      (*var)[i] = glm::vec4(count > 0 ? fb.variance(c, x, y) / float(count) : glm::vec3(0.0f), 0.0f);
      (*range)[i] = glm::vec4(fb.rangeColour(x, y), float(count));
      (*spread)[i] = glm::vec4(fb.rangeSpread(x, y), fb.rangeDepth(x, y), 0.0f, 0.0f);
    }
}

namespace {

// sigmaD in world units: a fraction of the depth extent of what the frame shows.
float depthSigma(const std::vector<float>& depth, float relative) {
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  for (float d : depth)
    if (std::isfinite(d)) lo = std::min(lo, d), hi = std::max(hi, d);
  if (!(hi >= lo)) return 1.0f;  // nothing was hit: depth plays no part
  // A frame of one plane facing the camera has no depth extent but the
  // rounding of its depths: measured from the distance instead.
  const float extent = hi - lo > 1e-4f * std::max(hi, 1.0f) ? hi - lo : std::max(hi, 1.0f);
  return std::max(relative * extent, 1e-6f);  // the filter's least sigma
}

}  // namespace

std::optional<std::uint32_t> PixelFilterResolver::filteredAt(std::uint64_t epoch) const {
  if (!filtered_ || filteredEpoch_ != epoch) return std::nullopt;
  return filtered_->samples;
}

void PixelFilterResolver::resolve(FrameBuffer& frame, const FilterSettings& settings, bool refilter, bool blendOutput,
                                  std::uint64_t epoch) {
  const std::size_t n = frame.colour.size();
  const auto low = rgbOf(requiredOutput(frame, kLowVarianceOutput, "pixel filtering"));
  const auto high = rgbOf(requiredOutput(frame, kHighVarianceOutput, "pixel filtering"));
  const auto var = rgbOf(requiredOutput(frame, kHighVarianceVarOutput, "pixel filtering"));
  const auto& rangeImage = requiredOutput(frame, kRangeOutput, "pixel filtering");  // samples in alpha
  const auto range = rgbOf(rangeImage);
  const auto& geometry = requiredOutput(frame, kRangeGeometryOutput, "pixel filtering");
  const auto spread = channelOf(geometry, 0), rangeDepth = channelOf(geometry, 1);
  std::uint32_t samples = 0;
  for (const glm::vec4& v : rangeImage) samples = std::max(samples, static_cast<std::uint32_t>(v.w));
  embree::PixelFilterInput input;
  input.width = frame.width;
  input.height = frame.height;
  input.lowVariance = low;
  input.highVariance = high;
  input.highVarianceVar = var;
  input.rangeColour = range;
  input.rangeDepth = rangeDepth;
  input.rangeSpread = spread;
  input.samples = samples;
  embree::PixelFilterSettings pixel = settings.pixel;
  pixel.sigmaD = depthSigma(rangeDepth, settings.sigmaDRelative);
  const bool stale = !filtered_ || filteredEpoch_ != epoch || filtered_->width != frame.width ||
                     filtered_->height != frame.height || filtered_->samples > samples;
  auto sameFilter = [](const embree::PixelFilterSettings& a, const embree::PixelFilterSettings& b) {
    return a.kernel == b.kernel && a.sigmaS == b.sigmaS && a.sigmaC == b.sigmaC && a.sigmaD == b.sigmaD &&
           a.adaptiveWidth == b.adaptiveWidth && a.antialiasRecovery == b.antialiasRecovery &&
           a.iterations == b.iterations && (!a.adaptiveWidth || a.threshold == b.threshold);
  };
  if (refilter || stale || !sameFilter(pixel, filteredWith_)) {
    filtered_ = embree::filterHighVariance(input, pixel);
    filteredWith_ = pixel;
    filteredEpoch_ = epoch;
  }
  embree::BlendResult blended = embree::blend(input, *filtered_, pixel);
  for (std::size_t i = 0; i < n; ++i) frame.colour[i] = glm::vec4(blended.radiance[i], frame.colour[i].a);
  if (blendOutput) {
    auto& s = frame.outputs[kBlendOutput];
    s.resize(n);
    for (std::size_t i = 0; i < n; ++i) s[i] = glm::vec4(glm::vec3(blended.blendFactor[i]), 1.0f);
  }
}

}  // namespace tsr::med::embree_mediator
