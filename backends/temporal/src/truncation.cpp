#include "tsr/temporal/truncation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tsr::temporal {

namespace {

// The median energy of the centred modes 2..N (mode 1 is the mean), or 0
// when there are too few of them to tell noise from signal.
double noiseLevel(const std::vector<double>& unexplained) {
  const std::size_t n = unexplained.size() - 1;
  if (n < 5) return 0.0;
  std::vector<double> energy;
  for (std::size_t x = 2; x <= n; ++x) energy.push_back(std::max(0.0, unexplained[x - 1] - unexplained[x]));
  std::nth_element(energy.begin(), energy.begin() + static_cast<std::ptrdiff_t>(energy.size() / 2), energy.end());
  return energy[energy.size() / 2];
}

// Separable Gaussian, clamped at the borders.
std::vector<float> blur(const std::vector<float>& in, std::uint32_t w, std::uint32_t h, double sigma) {
  if (sigma <= 0) return in;
  const int radius = static_cast<int>(std::ceil(3 * sigma));
  std::vector<float> kernel(static_cast<std::size_t>(2 * radius + 1));
  float* const tap = kernel.data() + radius;  // tap[k] for k in [-radius, radius]
  float sum = 0;
  for (int k = -radius; k <= radius; ++k) sum += tap[k] = static_cast<float>(std::exp(-0.5 * k * k / (sigma * sigma)));
  for (float& k : kernel) k /= sum;
  auto pass = [&](const std::vector<float>& src, bool horizontal) {
    std::vector<float> dst(src.size());
    for (int y = 0; y < static_cast<int>(h); ++y)
      for (int x = 0; x < static_cast<int>(w); ++x) {
        float acc = 0;
        for (int k = -radius; k <= radius; ++k) {
          const int sx = horizontal ? std::clamp(x + k, 0, static_cast<int>(w) - 1) : x;
          const int sy = horizontal ? y : std::clamp(y + k, 0, static_cast<int>(h) - 1);
          acc += tap[k] * src[static_cast<std::size_t>(sy) * w + static_cast<std::size_t>(sx)];
        }
        dst[static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x)] = acc;
      }
    return dst;
  };
  return pass(pass(in, true), false);
}

}  // namespace

int truncationFor(const std::vector<double>& unexplained, const TruncationRule& rule) {
  return truncationFor(unexplained, rule, rule.noiseAware ? noiseLevel(unexplained) : 0.0);
}

int truncationFor(const std::vector<double>& unexplained, const TruncationRule& rule, double noise) {
  const int n = static_cast<int>(unexplained.size()) - 1;
  if (n < 1) throw std::invalid_argument("temporal: truncation of an empty basis");
  const double changeLimit = std::max(rule.epsilonChange, noise);
  for (int x = 1; x < n; ++x) {
    const auto i = static_cast<std::size_t>(x);
    const double signalLeft = unexplained[i] - static_cast<double>(n - x) * noise;
    const double next = unexplained[i] - unexplained[i + 1] - noise;  // mode x + 1 beyond the noise
    if (signalLeft <= rule.epsilon && next <= changeLimit) return x;
  }
  return n;
}

std::vector<float> truncationMap(const PcaBasis& basis, const TruncationRule& rule, double sigma) {
  const std::size_t pixels = std::size_t{basis.width()} * basis.height();
  std::vector<float> map(pixels);
  // A pixel's noise level: its mean energy in the modes the whole frame's
  // rule calls noise (beyond the global M), pooled over its neighbours.
  // (The median of one pixel's own few modes would be too rough, and
  // biased low: it sees three channels per mode.)
  std::vector<float> noise(pixels, 0.0f);
  const int global = rule.noiseAware ? truncationFor(basis.unexplained(), rule) : basis.modes();
  if (global < basis.modes()) {
    for (std::size_t p = 0; p < pixels; ++p)
      noise[p] = static_cast<float>(basis.pixelUnexplained(p)[static_cast<std::size_t>(global)] /
                                    static_cast<double>(basis.modes() - global));
    noise = blur(noise, basis.width(), basis.height(), std::max(sigma, 2.0));
  }
  for (std::size_t p = 0; p < pixels; ++p)
    map[p] = static_cast<float>(truncationFor(basis.pixelUnexplained(p), rule, noise[p]));
  map = blur(map, basis.width(), basis.height(), sigma);
  for (float& m : map) m = std::clamp(m, 1.0f, static_cast<float>(basis.modes()));  // rounding of the blur
  return map;
}

Frame blendHighSamples(const Frame& reconstructed, const Frame& highSamples, const std::vector<float>& truncation,
                       float mMin, float mMax) {
  if (highSamples.width != reconstructed.width || highSamples.height != reconstructed.height ||
      truncation.size() != reconstructed.pixels() || highSamples.rgb.size() != reconstructed.rgb.size())
    throw std::invalid_argument("temporal: high-sample frame or truncation map of the wrong size");
  if (!(mMax > mMin)) throw std::invalid_argument("temporal: M_max must exceed M_min");
  Frame out = reconstructed;
  for (std::size_t p = 0; p < out.pixels(); ++p) {
    const float alpha = std::clamp((truncation[p] - mMin) / (mMax - mMin), 0.0f, 1.0f);
    for (std::size_t c = 0; c < 3; ++c)
      out.rgb[p * 3 + c] = (1 - alpha) * reconstructed.rgb[p * 3 + c] + alpha * highSamples.rgb[p * 3 + c];
  }
  return out;
}

std::vector<bool> needsHighSamples(const std::vector<float>& truncation, float mMin) {
  std::vector<bool> out(truncation.size());
  for (std::size_t p = 0; p < truncation.size(); ++p) out[p] = truncation[p] > mMin;
  return out;
}

}  // namespace tsr::temporal
