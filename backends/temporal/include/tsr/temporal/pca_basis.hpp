#pragma once
// The PCA of a frame stack (Meyer & Anderson, eq. 2), computed from the
// N x N Gram matrix of the frames so memory stays O(pixels x N).
//
// The frames are the columns of X (rows: every pixel's R, G and B, one
// temporal basis shared by the three channels: indirect colour changes
// with the light in all channels at once, and one basis sees three times
// the samples). Not mean-centred, as eq. 2: the first mode carries the
// sequence's average. X^T X = V diag(lambda) V^T with lambda descending;
// mode i is the image U_i = X v_i with temporal weights v_i(t), and the
// first M modes reconstruct frame t as sum_{i<M} U_i v_i(t).
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
  // Eigenvalues of the Gram matrix, descending (the energy of each mode).
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
  float mode(std::size_t row, int i) const { return images_[row * static_cast<std::size_t>(modes_) + i]; }
  double weight(int t, int i) const { return weights_[static_cast<std::size_t>(t) * modes_ + i]; }

  std::uint32_t width_ = 0, height_ = 0;
  int modes_ = 0;
  std::vector<double> energies_;
  std::vector<double> weights_;  // v_i(t), row t
  std::vector<float> images_;    // U_i, row = pixel * 3 + channel
};

}  // namespace tsr::temporal
