#pragma once

#include <glm/vec2.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace tsr::embree {

// Piecewise-constant 1D distribution over [0, 1) with n equal cells, also
// usable as a discrete distribution over n items.
class Distribution1D {
 public:
  Distribution1D() = default;
  explicit Distribution1D(std::span<const float> weights);

  std::size_t size() const { return func_.size(); }
  float integral() const { return integral_; }  // mean of the weights
  bool empty() const { return func_.empty() || !(sum_ > 0.0f); }

  std::uint32_t sampleDiscrete(float u, float* probability) const;
  float discreteProbability(std::uint32_t i) const { return func_[i] / sum_; }

  // Returns x in [0, 1) and its density.
  float sampleContinuous(float u, float* pdf, std::uint32_t* cell = nullptr) const;
  float density(std::uint32_t cell) const { return func_[cell] / integral_; }

 private:
  std::uint32_t findCell(float u) const;

  std::vector<float> func_;
  std::vector<float> cdf_;  // size n + 1, normalised, cdf_[n] == 1
  float sum_ = 0.0f;
  float integral_ = 0.0f;
};

// Piecewise-constant 2D distribution on [0,1)^2: a marginal over rows and one
// conditional per row. weights are row-major, width * height.
class Distribution2D {
 public:
  Distribution2D() = default;
  Distribution2D(std::span<const float> weights, std::uint32_t width, std::uint32_t height);

  bool empty() const { return marginal_.empty(); }
  glm::vec2 sample(const glm::vec2& u, float* pdf) const;
  float pdf(const glm::vec2& p) const;

 private:
  std::uint32_t width_ = 0;
  std::uint32_t height_ = 0;
  std::vector<Distribution1D> rows_;
  Distribution1D marginal_;
};

}  // namespace tsr::embree
