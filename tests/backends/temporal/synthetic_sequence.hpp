#pragma once
// Small synthetic frame stacks for the temporal tests: a smooth image whose
// brightness follows a curve in time, optional white noise, and helpers to
// compare stacks.
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "tsr/temporal/frame.hpp"

namespace tsr::temporal::test {

// frame t, pixel (x, y): value(x, y, t) in all three channels (scaled per
// channel so the channels differ).
inline std::vector<Frame> sequence(int frames, std::uint32_t w, std::uint32_t h,
                                   const std::function<float(std::uint32_t, std::uint32_t, int)>& value) {
  std::vector<Frame> out;
  for (int t = 0; t < frames; ++t) {
    Frame f(w, h);
    for (std::uint32_t y = 0; y < h; ++y)
      for (std::uint32_t x = 0; x < w; ++x)
        for (std::size_t c = 0; c < 3; ++c)
          f.rgb[(std::size_t{y} * w + x) * 3 + c] = value(x, y, t) * (1.0f - 0.2f * float(c));
    out.push_back(std::move(f));
  }
  return out;
}

inline std::vector<Frame> withNoise(std::vector<Frame> frames, float sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0f, sigma);
  for (auto& f : frames)
    for (float& v : f.rgb) v += noise(rng);
  return frames;
}

// Mean squared difference over every value of every frame (or of the
// pixels `keep` accepts).
inline double mse(const std::vector<Frame>& a, const std::vector<Frame>& b,
                  const std::function<bool(std::size_t pixel)>& keep = {}) {
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t t = 0; t < a.size(); ++t)
    for (std::size_t i = 0; i < a[t].rgb.size(); ++i) {
      if (keep && !keep(i / 3)) continue;
      const double d = double(a[t].rgb[i]) - b[t].rgb[i];
      sum += d * d;
      ++n;
    }
  return n ? sum / double(n) : 0.0;
}

inline double mean(const Frame& f) {
  double s = 0;
  for (float v : f.rgb) s += v;
  return s / double(f.rgb.size());
}

}  // namespace tsr::temporal::test
