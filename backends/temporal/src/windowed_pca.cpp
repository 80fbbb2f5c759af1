#include "tsr/temporal/windowed_pca.hpp"

#include <memory>
#include <stdexcept>
#include <string>

namespace tsr::temporal {

WindowedPca::WindowedPca(int window, int overlap, PcaSettings settings)
    : window_(window), overlap_(overlap), settings_(settings) {
  if (window < 2 || overlap < 0 || overlap >= window)
    throw std::invalid_argument("temporal: window " + std::to_string(window) + " with overlap " +
                                std::to_string(overlap) +
                                ": need a window of at least 2 frames and 0 <= overlap < window");
}

std::vector<DenoisedFrame> WindowedPca::push(Frame frame) {
  inputs_.push_back(std::move(frame));
  if (static_cast<int>(inputs_.size()) < window_) return {};
  return process(false);
}

std::vector<DenoisedFrame> WindowedPca::finish() {
  if (inputs_.size() > held_.size()) return process(true);
  // Only the overlap of the last window is left: it is final as it stands.
  std::vector<DenoisedFrame> out = std::move(held_);
  held_.clear();
  inputs_.clear();
  return out;
}

std::vector<DenoisedFrame> WindowedPca::process(bool last) {
  auto result = std::make_shared<PcaResult>(denoise(inputs_, settings_));
  ++windows_;
  std::vector<Frame> frames = std::move(result->frames);
  result->frames.clear();
  const int size = static_cast<int>(frames.size());
  std::vector<DenoisedFrame> out, held;
  for (int j = 0; j < size; ++j) {
    DenoisedFrame d{firstIndex_ + j, std::move(frames[static_cast<std::size_t>(j)]), result};
    if (j < static_cast<int>(held_.size())) {
      // Cross-fade from the previous window's basis to this one's.
      const float w = float(j + 1) / float(held_.size() + 1);
      const Frame& before = held_[static_cast<std::size_t>(j)].frame;
      for (std::size_t k = 0; k < d.frame.rgb.size(); ++k)
        d.frame.rgb[k] = (1 - w) * before.rgb[k] + w * d.frame.rgb[k];
      out.push_back(std::move(d));
    } else if (!last && j >= size - overlap_) {
      held.push_back(std::move(d));
    } else {
      out.push_back(std::move(d));
    }
  }
  held_ = std::move(held);
  if (last) {
    inputs_.clear();
  } else {
    inputs_.erase(inputs_.begin(), inputs_.end() - overlap_);
    firstIndex_ += size - overlap_;
  }
  return out;
}

}  // namespace tsr::temporal
