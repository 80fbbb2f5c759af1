#pragma once
// Relative mean squared error of an image against a reference, the metric
// of the filtering issue: the mean over pixels and RGB channels of
// (y_hat - y)^2 / (y^2 + eps) on linear HDR colour (eps = 0.01 keeps dark
// pixels from dominating). Shared by the quality harness and the property
// tests, so both measure the same thing.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

namespace tsr::quality {

inline constexpr double kRelMseEpsilon = 0.01;

// Throws std::invalid_argument when the images differ in size or are empty.
inline double relMse(const std::vector<glm::vec4>& image, const std::vector<glm::vec4>& reference) {
  if (image.size() != reference.size() || image.empty())
    throw std::invalid_argument("relMse: images of " + std::to_string(image.size()) + " and " +
                                std::to_string(reference.size()) + " pixels");
  double sum = 0;
  for (std::size_t i = 0; i < image.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double y = reference[i][c], d = double(image[i][c]) - y;
      sum += d * d / (y * y + kRelMseEpsilon);
    }
  return sum / (3.0 * double(image.size()));
}

// Flicker, the temporal issue's tRelMSE: the mean over pixels and RGB of
// ((y_hat_t - y_hat_{t-1}) - (y_t - y_{t-1}))^2 / (y_t^2 + eps), averaged
// over t = 1..N-1. Throws std::invalid_argument for mismatched sequences.
inline double temporalRelMse(const std::vector<std::vector<glm::vec4>>& images,
                             const std::vector<std::vector<glm::vec4>>& references) {
  if (images.size() != references.size() || images.size() < 2)
    throw std::invalid_argument("temporalRelMse: needs two or more frames on each side, equally many");
  double total = 0;
  for (std::size_t t = 1; t < images.size(); ++t) {
    const auto &a = images[t], &a0 = images[t - 1], &y = references[t], &y0 = references[t - 1];
    if (a.size() != y.size() || a0.size() != y.size() || y0.size() != y.size() || y.empty())
      throw std::invalid_argument("temporalRelMse: frames of different sizes");
    double sum = 0;
    for (std::size_t i = 0; i < y.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        const double d = (double(a[i][c]) - a0[i][c]) - (double(y[i][c]) - y0[i][c]);
        sum += d * d / (double(y[i][c]) * y[i][c] + kRelMseEpsilon);
      }
    total += sum / (3.0 * double(y.size()));
  }
  return total / double(images.size() - 1);
}

// The mean of channel r of an output (e.g. the blend factor s).
inline double meanRed(const std::vector<glm::vec4>& image) {
  if (image.empty()) return 0;
  double sum = 0;
  for (const auto& p : image) sum += p.r;
  return sum / double(image.size());
}

}  // namespace tsr::quality
