#pragma once
// Sequences longer than memory allows, denoised in overlapping windows:
// frames are pushed in order; every `window` frames the stack is denoised,
// the next window starts `overlap` frames before the last one ended, and
// in the overlap the two windows' reconstructions are cross-faded linearly
// so no seam shows where one basis hands over to the next. At most
// `window` input frames and `overlap` reconstructions are held.
#include <deque>
#include <memory>
#include <vector>

#include "tsr/temporal/pca_denoise.hpp"

namespace tsr::temporal {

struct DenoisedFrame {
  int index = 0;  // position in the whole sequence
  Frame frame;
  std::shared_ptr<const PcaResult> window;  // the window it came from (truncation map, modes); frames moved out
};

class WindowedPca {
 public:
  // Throws std::invalid_argument unless 2 <= window and 0 <= overlap < window.
  WindowedPca(int window, int overlap, PcaSettings settings);

  // Frames finished by this push (none until a window is full).
  std::vector<DenoisedFrame> push(Frame frame);
  // Denoises what is left and returns the remaining frames.
  std::vector<DenoisedFrame> finish();
  // Windows denoised so far.
  int windows() const { return windows_; }

 private:
  std::vector<DenoisedFrame> process(bool last);

  int window_, overlap_;
  PcaSettings settings_;
  std::vector<Frame> inputs_;        // the current window's frames
  int firstIndex_ = 0;               // sequence index of inputs_[0]
  std::vector<DenoisedFrame> held_;  // the previous window's overlap, not yet emitted
  int windows_ = 0;
};

}  // namespace tsr::temporal
