#include "tsr/temporal/pca_basis.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Dense>

namespace tsr::temporal {

namespace {
// Rows of X gathered per block, so the Gram matrix is summed in double
// without a double copy of the whole stack.
constexpr std::size_t kBlockRows = 4096;

// Rows [row0, row0 + rows) of X minus their temporal mean.
Eigen::MatrixXd centredBlock(const std::vector<Frame>& frames, const std::vector<float>& mean, std::size_t row0,
                             std::size_t rows) {
  Eigen::MatrixXd b(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(frames.size()));
  for (std::size_t t = 0; t < frames.size(); ++t)
    for (std::size_t r = 0; r < rows; ++r)
      b(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(t)) = double(frames[t].rgb[row0 + r]) - mean[row0 + r];
  return b;
}
}  // namespace

PcaBasis::PcaBasis(const std::vector<Frame>& frames) {
  checkSequence(frames);
  width_ = frames.front().width;
  height_ = frames.front().height;
  modes_ = static_cast<int>(frames.size());
  const std::size_t rows = frames.front().rgb.size();
  const auto n = static_cast<Eigen::Index>(modes_);

  std::vector<double> sum(rows, 0.0);
  for (const auto& f : frames)
    for (std::size_t r = 0; r < rows; ++r) sum[r] += f.rgb[r];
  mean_.resize(rows);
  double meanEnergy = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    mean_[r] = static_cast<float>(sum[r] / double(n));
    meanEnergy += double(n) * mean_[r] * mean_[r];
  }

  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t r = 0; r < rows; r += kBlockRows) {
    const Eigen::MatrixXd b = centredBlock(frames, mean_, r, std::min(kBlockRows, rows - r));
    gram.noalias() += b.transpose() * b;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(gram);
  if (solver.info() != Eigen::Success)
    throw std::runtime_error("temporal: eigen-decomposition of the Gram matrix failed");
  // Eigen sorts ascending; modes are wanted descending. The centred Gram
  // matrix has rank N - 1 at most (the constant vector is in its null
  // space): its smallest eigenvector is dropped, the mean takes its place.
  const Eigen::MatrixXd v = solver.eigenvectors().rowwise().reverse().leftCols(n - 1);
  energies_.assign(1, meanEnergy);
  for (Eigen::Index i = 0; i + 1 < n; ++i) energies_.push_back(std::max(0.0, solver.eigenvalues()(n - 1 - i)));
  weights_.assign(static_cast<std::size_t>(modes_) * modes_, 0.0);
  for (Eigen::Index t = 0; t < n; ++t)
    for (Eigen::Index i = 1; i < n; ++i) weights_[static_cast<std::size_t>(t * n + i)] = v(t, i - 1);

  images_.resize(rows * static_cast<std::size_t>(modes_ - 1));
  if (modes_ == 1) return;
  for (std::size_t r = 0; r < rows; r += kBlockRows) {
    const std::size_t count = std::min(kBlockRows, rows - r);
    const Eigen::MatrixXd u = centredBlock(frames, mean_, r, count) * v;
    for (std::size_t k = 0; k < count; ++k)
      for (Eigen::Index i = 0; i + 1 < n; ++i)
        images_[(r + k) * static_cast<std::size_t>(modes_ - 1) + static_cast<std::size_t>(i)] =
            static_cast<float>(u(static_cast<Eigen::Index>(k), i));
  }
}

std::vector<double> PcaBasis::unexplained() const {
  double total = 0;
  for (double e : energies_) total += e;
  std::vector<double> out(static_cast<std::size_t>(modes_) + 1, 0.0);
  double left = total;
  for (int x = 0; x <= modes_; ++x) {
    out[static_cast<std::size_t>(x)] = total > 0 ? std::max(0.0, left / total) : 0.0;
    if (x < modes_) left -= energies_[static_cast<std::size_t>(x)];
  }
  return out;
}

std::vector<double> PcaBasis::pixelUnexplained(std::size_t pixel) const {
  // The weights are orthonormal in time and orthogonal to the constant, so
  // the mean adds N mu(p)^2 and mode i adds U_i(p)^2 of the pixel's energy.
  std::vector<double> cumulative(static_cast<std::size_t>(modes_) + 1, 0.0);
  for (int i = 0; i < modes_; ++i) {
    double e = 0;
    for (std::size_t c = 0; c < 3; ++c) {
      const std::size_t row = pixel * 3 + c;
      e += i == 0 ? double(modes_) * mean_[row] * mean_[row] : double(mode(row, i)) * mode(row, i);
    }
    cumulative[static_cast<std::size_t>(i) + 1] = cumulative[static_cast<std::size_t>(i)] + e;
  }
  const double total = cumulative.back();
  std::vector<double> out(cumulative.size());
  for (std::size_t x = 0; x < out.size(); ++x) out[x] = total > 0 ? std::max(0.0, 1.0 - cumulative[x] / total) : 0.0;
  return out;
}

Frame PcaBasis::reconstruct(int t, int modes) const {
  if (t < 0 || t >= modes_ || modes < 0 || modes > modes_)
    throw std::out_of_range("temporal: frame " + std::to_string(t) + " with " + std::to_string(modes) + " of " +
                            std::to_string(modes_) + " modes");
  return reconstruct(t, std::vector<float>(std::size_t{width_} * height_, static_cast<float>(modes)));
}

Frame PcaBasis::reconstruct(int t, const std::vector<float>& truncation) const {
  if (t < 0 || t >= modes_)
    throw std::out_of_range("temporal: frame " + std::to_string(t) + " of " + std::to_string(modes_));
  Frame out(width_, height_);
  if (truncation.size() != out.pixels()) throw std::invalid_argument("temporal: truncation map of the wrong size");
  for (std::size_t p = 0; p < out.pixels(); ++p) {
    const float m = std::clamp(truncation[p], 0.0f, static_cast<float>(modes_));
    const int whole = static_cast<int>(m);
    const float part = m - static_cast<float>(whole);
    for (std::size_t c = 0; c < 3; ++c) {
      const std::size_t row = p * 3 + c;
      auto term = [&](int i) { return i == 0 ? double(mean_[row]) : mode(row, i) * weight(t, i); };
      double sum = 0;
      for (int i = 0; i < whole; ++i) sum += term(i);
      if (whole < modes_ && part > 0) sum += part * term(whole);
      out.rgb[row] = static_cast<float>(sum);
    }
  }
  return out;
}

}  // namespace tsr::temporal
