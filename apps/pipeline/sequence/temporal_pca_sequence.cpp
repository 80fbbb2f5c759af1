#include "sequence/temporal_pca_sequence.hpp"

#include <algorithm>
#include <stdexcept>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace tsr::app {

namespace {
constexpr const char* kDirect = "direct";
constexpr const char* kIndirect = "indirect";

double since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

temporal::PcaSettings pcaSettings(const TemporalOptions& o) {
  temporal::PcaSettings s;
  s.rule.epsilon = o.epsilon;
  s.rule.epsilonChange = o.epsilonChange;
  s.rule.noiseAware = !o.plainRule;
  s.fixedModes = o.modes;
  s.perPixel = !o.global;
  s.mapSigma = o.mapSigma;
  return s;
}

temporal::Frame toTemporalFrame(const std::vector<glm::vec4>& pixels, std::uint32_t width, std::uint32_t height) {
  temporal::Frame f(width, height);
  if (pixels.size() != f.pixels()) throw std::invalid_argument("temporal: an output of the wrong size");
  for (std::size_t p = 0; p < pixels.size(); ++p)
    for (int c = 0; c < 3; ++c) f.rgb[p * 3 + static_cast<std::size_t>(c)] = pixels[p][c];
  return f;
}

TemporalPcaSequence::TemporalPcaSequence(const TemporalOptions& options, Writer write, HighSamples highSamples)
    : pca_(options.window, options.overlapFrames(), pcaSettings(options)),
      write_(std::move(write)),
      highSamples_(std::move(highSamples)),
      mMin_(options.mMin) {}

void TemporalPcaSequence::add(int frame, med::FrameBuffer image) {
  if (!image.outputs.count(kDirect) || !image.outputs.count(kIndirect))
    throw std::invalid_argument(
        "--temporal pca: the back-end returned no direct/indirect outputs (use --backend embree)");
  temporal::Frame indirect = toTemporalFrame(image.outputs[kIndirect], image.width, image.height);
  waiting_.emplace(frame, std::move(image));
  const auto start = std::chrono::steady_clock::now();
  auto ready = pca_.push(std::move(indirect));
  seconds_ += since(start);
  emit(std::move(ready));
}

void TemporalPcaSequence::finish() {
  const auto start = std::chrono::steady_clock::now();
  auto ready = pca_.finish();
  seconds_ += since(start);
  emit(std::move(ready));
}

void TemporalPcaSequence::emit(std::vector<temporal::DenoisedFrame> ready) {
  for (auto& d : ready) {
    if (d.window.get() != lastWindow_) {
      lastWindow_ = d.window.get();
      modeSum_ += d.window->meanTruncation();
      ++windowsCounted_;
    }
    auto it = waiting_.find(d.index);
    if (it == waiting_.end())
      throw std::logic_error("temporal: frame " + std::to_string(d.index) + " was never rendered");
    med::FrameBuffer image = std::move(it->second);
    waiting_.erase(it);
    if (highSamples_) {
      // 3.2: where the map keeps many modes, blend towards a render with more samples.
      const auto& map = d.window->truncation;
      const float mMax = static_cast<float>(d.window->availableModes);
      const float mMin = mMin_ > 0 ? static_cast<float>(mMin_) : mMax / 2;
      const std::vector<bool> need = temporal::needsHighSamples(map, mMin);
      if (mMin < mMax && std::find(need.begin(), need.end(), true) != need.end()) {
        const temporal::Frame high = toTemporalFrame(highSamples_(d.index, need), image.width, image.height);
        d.frame = temporal::blendHighSamples(d.frame, high, map, mMin, mMax);
      }
    }
    // The beauty is direct + denoised indirect; coverage (alpha) stays.
    const auto& direct = image.outputs[kDirect];
    auto& indirect = image.outputs[kIndirect];
    for (std::size_t p = 0; p < image.colour.size(); ++p) {
      // A projection can dip under zero where the noise was; radiance cannot.
      const glm::vec3 denoised =
          glm::max(glm::vec3(d.frame.rgb[p * 3], d.frame.rgb[p * 3 + 1], d.frame.rgb[p * 3 + 2]), 0.0f);
      indirect[p] = glm::vec4(denoised, 1.0f);
      image.colour[p] = glm::vec4(glm::vec3(direct[p]) + denoised, image.colour[p].a);
    }
    write_(d.index, image);
  }
}

}  // namespace tsr::app
