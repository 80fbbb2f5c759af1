#pragma once
// The temporal step of `--temporal pca`, on the client: rendered frames
// (with their "direct" and "indirect" outputs) arrive in order; the
// indirect light is denoised over time in overlapping windows, and each
// finished frame is written as direct + denoised indirect, its "indirect"
// output replaced by the denoised one.
#include <chrono>
#include <functional>
#include <map>
#include <memory>

#include "sequence/temporal_options.hpp"
#include "tsr/med/frame_buffer.hpp"
#include "tsr/temporal/windowed_pca.hpp"

namespace tsr::app {

class TemporalPcaSequence {
 public:
  using Writer = std::function<void(int frame, const med::FrameBuffer& image)>;
  // The indirect light of a frame at more samples, on the pixels flagged
  // (3.2's importance sampling; high_sample_frames.hpp).
  using HighSamples = std::function<std::vector<glm::vec4>(int frame, const std::vector<bool>& need)>;
  TemporalPcaSequence(const TemporalOptions& options, Writer write, HighSamples highSamples = {});

  // Throws std::invalid_argument when the frame lacks direct or indirect.
  void add(int frame, med::FrameBuffer image);
  void finish();

  double denoiseSeconds() const { return seconds_; }
  int windows() const { return pca_.windows(); }
  // The mean of the per-pixel truncation over the windows seen (or the
  // global M): how many modes the frames kept.
  double meanModes() const { return windowsCounted_ ? modeSum_ / windowsCounted_ : 0; }

 private:
  void emit(std::vector<temporal::DenoisedFrame> ready);

  temporal::WindowedPca pca_;
  Writer write_;
  HighSamples highSamples_;
  double mMin_ = 0;
  std::map<int, med::FrameBuffer> waiting_;  // rendered, indirect not denoised yet
  double seconds_ = 0;
  const temporal::PcaResult* lastWindow_ = nullptr;
  double modeSum_ = 0;
  int windowsCounted_ = 0;
};

// Settings of the PCA step the options name.
temporal::PcaSettings pcaSettings(const TemporalOptions& options);

// A FrameBuffer output as a temporal frame and back.
temporal::Frame toTemporalFrame(const std::vector<glm::vec4>& pixels, std::uint32_t width, std::uint32_t height);

}  // namespace tsr::app
