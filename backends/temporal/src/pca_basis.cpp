#include "tsr/temporal/pca_basis.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>

namespace tsr::temporal {

namespace {
// Rows of X gathered per block, so the Gram matrix is summed in double
// without a double copy of the whole stack.
constexpr std::size_t kBlockRows = 4096;

Eigen::MatrixXd block(const std::vector<Frame>& frames, std::size_t row0, std::size_t rows) {
  Eigen::MatrixXd b(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(frames.size()));
  for (std::size_t t = 0; t < frames.size(); ++t)
    for (std::size_t r = 0; r < rows; ++r) b(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(t)) = frames[t].rgb[row0 + r];
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

  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t r = 0; r < rows; r += kBlockRows) {
    const Eigen::MatrixXd b = block(frames, r, std::min(kBlockRows, rows - r));
    gram.noalias() += b.transpose() * b;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(gram);
  if (solver.info() != Eigen::Success) throw std::runtime_error("temporal: eigen-decomposition of the Gram matrix failed");
  // Eigen sorts ascending; modes are wanted descending.
  Eigen::MatrixXd v = solver.eigenvectors().rowwise().reverse();
  energies_.resize(static_cast<std::size_t>(modes_));
  for (Eigen::Index i = 0; i < n; ++i) energies_[static_cast<std::size_t>(i)] = std::max(0.0, solver.eigenvalues()(n - 1 - i));
  weights_.resize(static_cast<std::size_t>(modes_) * modes_);
  for (Eigen::Index t = 0; t < n; ++t)
    for (Eigen::Index i = 0; i < n; ++i) weights_[static_cast<std::size_t>(t * n + i)] = v(t, i);

  images_.resize(rows * static_cast<std::size_t>(modes_));
  for (std::size_t r = 0; r < rows; r += kBlockRows) {
    const std::size_t count = std::min(kBlockRows, rows - r);
    const Eigen::MatrixXd u = block(frames, r, count) * v;
    for (std::size_t k = 0; k < count; ++k)
      for (Eigen::Index i = 0; i < n; ++i)
        images_[(r + k) * static_cast<std::size_t>(modes_) + static_cast<std::size_t>(i)] =
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
  // The weights are orthonormal in time, so mode i adds U_i(p)^2 of the
  // pixel's energy sum_t X(p, t)^2.
  std::vector<double> cumulative(static_cast<std::size_t>(modes_) + 1, 0.0);
  for (int i = 0; i < modes_; ++i) {
    double e = 0;
    for (std::size_t c = 0; c < 3; ++c) e += double(mode(pixel * 3 + c, i)) * mode(pixel * 3 + c, i);
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
  if (t < 0 || t >= modes_) throw std::out_of_range("temporal: frame " + std::to_string(t) + " of " + std::to_string(modes_));
  Frame out(width_, height_);
  if (truncation.size() != out.pixels()) throw std::invalid_argument("temporal: truncation map of the wrong size");
  for (std::size_t p = 0; p < out.pixels(); ++p) {
    const float m = std::clamp(truncation[p], 0.0f, static_cast<float>(modes_));
    const int whole = static_cast<int>(m);
    const float part = m - static_cast<float>(whole);
    for (std::size_t c = 0; c < 3; ++c) {
      const std::size_t row = p * 3 + c;
      double sum = 0;
      for (int i = 0; i < whole; ++i) sum += mode(row, i) * weight(t, i);
      if (whole < modes_ && part > 0) sum += part * mode(row, whole) * weight(t, whole);
      out.rgb[row] = static_cast<float>(sum);
    }
  }
  return out;
}

}  // namespace tsr::temporal
