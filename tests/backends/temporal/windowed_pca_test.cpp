// Overlapping windows: every frame comes out once, in order; a sequence
// the basis can hold exactly survives the hand-over; noise is reduced as
// in one window and the boundary shows no seam.
#include <gtest/gtest.h>

#include "synthetic_sequence.hpp"
#include "tsr/temporal/windowed_pca.hpp"

namespace tsr::temporal {
namespace {

std::vector<Frame> drifting(int frames) {
  return test::sequence(frames, 12, 10, [](std::uint32_t x, std::uint32_t y, int t) {
    return 1.0f + 0.4f * std::sin(0.5f * float(x) + 0.3f * float(y)) + 0.02f * float(t) * float(x) / 12.0f;
  });
}

std::vector<Frame> run(WindowedPca& w, const std::vector<Frame>& input) {
  std::vector<Frame> out;
  auto take = [&](std::vector<DenoisedFrame> ready) {
    for (auto& d : ready) {
      EXPECT_EQ(d.index, static_cast<int>(out.size()));
      out.push_back(std::move(d.frame));
    }
  };
  for (const auto& f : input) take(w.push(f));
  take(w.finish());
  return out;
}

TEST(WindowedPca, EmitsEveryFrameOnceAndReproducesALowRankSequence) {
  const auto clean = drifting(23);
  PcaSettings s;
  s.fixedModes = 2;  // the sequence is rank 2
  WindowedPca w(8, 3, s);
  const auto out = run(w, clean);
  ASSERT_EQ(out.size(), clean.size());
  EXPECT_GE(w.windows(), 4);
  EXPECT_LT(test::mse(out, clean), 1e-8);
}

TEST(WindowedPca, DenoisesWithoutASeamAtWindowBoundaries) {
  const auto clean = drifting(40);
  const auto noisy = test::withNoise(clean, 0.03f, 3);
  PcaSettings s;
  s.perPixel = false;
  WindowedPca w(16, 6, s);
  const auto out = run(w, noisy);
  ASSERT_EQ(out.size(), clean.size());
  EXPECT_LT(test::mse(out, clean), test::mse(noisy, clean) / 4);
  // Temporal error of the frame-to-frame change, per step: the steps across
  // a window's hand-over (frames 10..16, 20..26, 30..36) are no worse than
  // the worst step inside a window.
  auto stepError = [&](std::size_t t) {
    double e = 0;
    for (std::size_t i = 0; i < out[t].rgb.size(); ++i) {
      const double d = (double(out[t].rgb[i]) - out[t - 1].rgb[i]) - (double(clean[t].rgb[i]) - clean[t - 1].rgb[i]);
      e += d * d;
    }
    return e / double(out[t].rgb.size());
  };
  double inside = 0, across = 0;
  for (std::size_t t = 1; t < out.size(); ++t) {
    const bool handOver = (t >= 10 && t <= 16) || (t >= 20 && t <= 26) || (t >= 30 && t <= 36);
    (handOver ? across : inside) = std::max(handOver ? across : inside, stepError(t));
  }
  EXPECT_LT(across, 2 * inside);
  // And every step is far below the noisy sequence's.
  EXPECT_LT(across, 2 * 0.03 * 0.03 / 4);
}

TEST(WindowedPca, RefusesImpossibleWindows) {
  EXPECT_THROW(WindowedPca(1, 0, {}), std::invalid_argument);
  EXPECT_THROW(WindowedPca(8, 8, {}), std::invalid_argument);
  EXPECT_THROW(WindowedPca(8, -1, {}), std::invalid_argument);
}

}  // namespace
}  // namespace tsr::temporal
