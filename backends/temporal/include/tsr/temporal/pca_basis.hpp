#pragma once
// The PCA of a frame stack (Meyer & Anderson, eq. 2), computed from the
// N x N Gram matrix of the frames so memory stays O(pixels x N).
//
// The frames are the columns of X (rows: every pixel's R, G and B, one
// temporal basis shared by the three channels: indirect colour changes
// with the light in all channels at once, and one basis sees three times
// the samples). Mode 0 is each row's temporal mean; modes 1..N-1 are the
// principal components of X minus that mean: X'^T X' = V diag(lambda) V^T,
// lambda descending, mode i the image U_i = X' v_i with temporal weights
// v_i(t). Frame t from the first M modes is mean + sum_{i<M-1} U_i v_i(t).
// Centring per pixel (eq. 2 does not) is what lets a static pixel stop at
// one mode in 3.2's per-pixel truncation: uncentred, the first mode's
// temporal weight carries whatever changes elsewhere in the frame. Energies
// stay uncentred fractions (the mean's energy counts), so 2.3's epsilon
// keeps its meaning: mode 0 is the paper's first mode.
#include <cstddef>
#include <vector>

#include "tsr/temporal/frame.hpp"

namespace tsr::temporal {

class PcaBasis {
 public:
  // Throws std::invalid_argument for an empty or inconsistent stack.
  explicit PcaBasis(const std::vector<Frame>& frames);

  int modes() const { return modes_; }
  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }
  // The energy of each mode: the mean's, then the centred Gram matrix's
  // eigenvalues, descending.
  const std::vector<double>& energies() const { return energies_; }

  // percentVar(x) of 2.3 as a fraction: the energy the first x modes leave
  // unexplained, for x = 0..modes().
  std::vector<double> unexplained() const;
  // The same for one pixel (its three channels together).
  std::vector<double> pixelUnexplained(std::size_t pixel) const;

  // Frame t from the first `modes` modes (0..modes()).
  Frame reconstruct(int t, int modes) const;
  // Frame t with a per-pixel truncation: pixel p uses floor(m) modes plus
  // the fraction m - floor(m) of the next one (3.2's interpolation between
  // neighbouring reconstructions). `truncation` holds one m per pixel.
  Frame reconstruct(int t, const std::vector<float>& truncation) const;

 private:
  // Mode i >= 1 of a row.
  float mode(std::size_t row, int i) const {
    return images_[row * static_cast<std::size_t>(modes_ - 1) + static_cast<std::size_t>(i - 1)];
  }
  double weight(int t, int i) const {
    return weights_[static_cast<std::size_t>(t) * modes_ + static_cast<std::size_t>(i)];
  }

  std::uint32_t width_ = 0, height_ = 0;
  int modes_ = 0;
  std::vector<double> energies_;
  std::vector<double> weights_;  // v_i(t), row t
  std::vector<float> mean_;      // mode 0, per row
  std::vector<float> images_;    // U_i of modes 1..N-1 (index i - 1), row = pixel * 3 + channel
};

}  // namespace tsr::temporal
