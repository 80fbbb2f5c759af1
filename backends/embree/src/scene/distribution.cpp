#include "tsr/embree/distribution.hpp"

#include "tsr/embree/error.hpp"

#include <algorithm>
#include <cmath>

namespace tsr::embree {

Distribution1D::Distribution1D(std::span<const float> weights) : func_(weights.begin(), weights.end()) {
  cdf_.resize(func_.size() + 1, 0.0f);
  // Accumulate in double so long light lists keep their small entries.
  double sum = 0.0;
  for (std::size_t i = 0; i < func_.size(); ++i) {
    if (!(func_[i] >= 0.0f) || !std::isfinite(func_[i])) throw Error("distribution weight is negative or not finite");
    sum += func_[i];
    cdf_[i + 1] = float(sum);
  }
  sum_ = float(sum);
  integral_ = func_.empty() ? 0.0f : float(sum / double(func_.size()));
  if (sum > 0.0) {
    for (std::size_t i = 1; i <= func_.size(); ++i) cdf_[i] = float(double(cdf_[i]) / sum);
    cdf_.back() = 1.0f;
  }
}

std::uint32_t Distribution1D::findCell(float u) const {
  // Largest i with cdf_[i] <= u, skipping zero-weight cells.
  auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
  auto i = std::uint32_t(std::clamp<std::ptrdiff_t>(it - cdf_.begin() - 1, 0, std::ptrdiff_t(func_.size()) - 1));
  while (func_[i] <= 0.0f && i + 1 < func_.size()) ++i;
  while (func_[i] <= 0.0f && i > 0) --i;
  return i;
}

std::uint32_t Distribution1D::sampleDiscrete(float u, float* probability) const {
  std::uint32_t i = findCell(u);
  if (probability) *probability = func_[i] / sum_;
  return i;
}

float Distribution1D::sampleContinuous(float u, float* pdf, std::uint32_t* cell) const {
  std::uint32_t i = findCell(u);
  float width = cdf_[i + 1] - cdf_[i];
  float du = width > 0.0f ? (u - cdf_[i]) / width : 0.5f;
  du = std::clamp(du, 0.0f, 1.0f);
  if (pdf) *pdf = func_[i] / integral_;
  if (cell) *cell = i;
  float x = (float(i) + du) / float(func_.size());
  return std::min(x, 1.0f - 0x1p-24f);
}

Distribution2D::Distribution2D(std::span<const float> weights, std::uint32_t width, std::uint32_t height)
    : width_(width), height_(height) {
  if (weights.size() != std::size_t(width) * height || width == 0 || height == 0) {
    throw Error("2D distribution size does not match its weights");
  }
  rows_.reserve(height);
  std::vector<float> marginal(height);
  for (std::uint32_t y = 0; y < height; ++y) {
    rows_.emplace_back(weights.subspan(std::size_t(y) * width, width));
    marginal[y] = rows_.back().integral();
  }
  marginal_ = Distribution1D(marginal);
}

glm::vec2 Distribution2D::sample(const glm::vec2& u, float* pdf) const {
  float pdfY = 0.0f;
  float pdfX = 0.0f;
  std::uint32_t row = 0;
  float y = marginal_.sampleContinuous(u.y, &pdfY, &row);
  float x = rows_[row].sampleContinuous(u.x, &pdfX);
  if (pdf) *pdf = pdfX * pdfY;
  return {x, y};
}

float Distribution2D::pdf(const glm::vec2& p) const {
  auto x = std::uint32_t(std::clamp(int(p.x * float(width_)), 0, int(width_) - 1));
  auto y = std::uint32_t(std::clamp(int(p.y * float(height_)), 0, int(height_) - 1));
  if (marginal_.empty() || rows_[y].empty()) return 0.0f;
  return rows_[y].density(x) * marginal_.density(y);
}

}  // namespace tsr::embree
