// Truncation (2.3, 3.2): white noise is projected away, a step in the
// light is kept, and the per-pixel map spends modes only where the
// sequence changes.
#include <gtest/gtest.h>

#include "synthetic_sequence.hpp"
#include "tsr/temporal/pca_denoise.hpp"
#include "tsr/temporal/truncation.hpp"

namespace tsr::temporal {
namespace {

constexpr int kFrames = 24;
constexpr std::uint32_t kSize = 16;

float pattern(std::uint32_t x, std::uint32_t y) {
  return 1.0f + 0.5f * std::sin(float(x) / 3.0f) * std::cos(float(y) / 4.0f);
}

// A light switched on harder at frame 12 plus a slow drift of another
// pattern: rank 2, with a discontinuity in time.
std::vector<Frame> switchedLight() {
  return test::sequence(kFrames, kSize, kSize, [](std::uint32_t x, std::uint32_t y, int t) {
    return pattern(x, y) * (t < 12 ? 1.0f : 2.5f) + 0.3f * float(x) / kSize * float(t) / kFrames;
  });
}

TEST(Truncation, RuleTakesTheFirstModeCountThatExplainsEnoughAndStopsImproving) {
  const TruncationRule rule;  // 0.005, 0.001
  EXPECT_EQ(truncationFor({1.0, 0.1, 0.004, 0.0035, 0.0}, rule), 2);
  EXPECT_EQ(truncationFor({1.0, 0.1, 0.004, 0.001, 0.0}, rule), 3);  // mode 3 still improves by 0.003
  EXPECT_EQ(truncationFor({1.0, 0.2, 0.1, 0.05, 0.0}, rule), 4);     // never close enough: every mode
  EXPECT_THROW(truncationFor({1.0}, rule), std::invalid_argument);
}

TEST(Truncation, RemovesWhiteNoiseAndKeepsAStep) {
  const auto clean = switchedLight();
  const auto noisy = test::withNoise(clean, 0.03f, 5);
  PcaSettings settings;
  settings.perPixel = false;
  const PcaResult r = denoise(noisy, settings);
  EXPECT_GE(r.globalModes, 2);
  EXPECT_LE(r.globalModes, 4);
  EXPECT_LT(test::mse(r.frames, clean), test::mse(noisy, clean) / 5);
  // The switch stays a one-frame step: not spread over its neighbours.
  const double step = test::mean(clean[12]) - test::mean(clean[11]);
  EXPECT_NEAR(test::mean(r.frames[12]) - test::mean(r.frames[11]), step, 0.03 * step);
  EXPECT_NEAR(test::mean(r.frames[11]) - test::mean(r.frames[10]), test::mean(clean[11]) - test::mean(clean[10]),
              0.01 * step);
  EXPECT_NEAR(test::mean(r.frames[13]) - test::mean(r.frames[12]), test::mean(clean[13]) - test::mean(clean[12]),
              0.01 * step);
}

// Noise as a path tracer leaves it at few samples (30 % of the signal, not
// 3 %): every mode then improves on the fixed epsilonChange, so 2.3's rule
// alone keeps them all; measuring the noise keeps the signal's modes only.
TEST(Truncation, NoiseAwareRuleStopsAtTheSignalUnderHeavyNoise) {
  const auto clean = switchedLight();
  const auto noisy = test::withNoise(clean, 0.3f, 7);
  PcaSettings settings;
  settings.perPixel = false;
  settings.rule.noiseAware = false;
  const PcaResult fixed = denoise(noisy, settings);
  EXPECT_GT(fixed.globalModes, kFrames / 2) << "2.3 with a fixed epsilonChange keeps the noise";
  settings.rule.noiseAware = true;
  const PcaResult aware = denoise(noisy, settings);
  EXPECT_GE(aware.globalModes, 2);
  EXPECT_LE(aware.globalModes, 4);
  EXPECT_LT(test::mse(aware.frames, clean), test::mse(fixed.frames, clean) / 4);
  const double step = test::mean(clean[12]) - test::mean(clean[11]);
  EXPECT_NEAR(test::mean(aware.frames[12]) - test::mean(aware.frames[11]), step, 0.05 * step) << "the switch stays";
  // The per-pixel map measures each pixel's own noise the same way.
  settings.perPixel = true;
  const PcaResult map = denoise(noisy, settings);
  EXPECT_LT(map.meanTruncation(), 6.0);
  EXPECT_LT(test::mse(map.frames, clean), test::mse(fixed.frames, clean) / 2);
}

// Left half static, right half a bright spot moving down a column: the
// right half needs many modes, the left one.
std::vector<Frame> movingSpot() {
  return test::sequence(kFrames, kSize, kSize, [](std::uint32_t x, std::uint32_t y, int t) {
    if (x < kSize / 2) return pattern(x, y);
    const float d = float(y) - float(t) * float(kSize) / kFrames;
    return 0.5f + 2.0f * std::exp(-0.5f * d * d);
  });
}

TEST(Truncation, PerPixelMapSpendsModesWhereTheSequenceChanges) {
  const auto clean = movingSpot();
  const auto noisy = test::withNoise(clean, 0.02f, 9);
  PcaSettings perPixel;
  const PcaResult r = denoise(noisy, perPixel);
  auto left = [](std::size_t p) { return p % kSize < kSize / 2 - 3; };
  auto right = [](std::size_t p) { return p % kSize >= kSize / 2 + 3; };
  double mLeft = 0, mRight = 0;
  for (std::size_t p = 0; p < r.truncation.size(); ++p) {
    EXPECT_GE(r.truncation[p], 1.0f);
    EXPECT_LE(r.truncation[p], float(kFrames));
    if (left(p)) mLeft += r.truncation[p] / (5.0 * kSize);
    if (right(p)) mRight += r.truncation[p] / (5.0 * kSize);
  }
  EXPECT_LT(mLeft, 1.5);
  EXPECT_GT(mRight, 4 * mLeft);
  // Smoothed: no jump between neighbours larger than a fraction of the range.
  for (std::size_t p = 0; p + 1 < r.truncation.size(); ++p)
    if ((p + 1) % kSize != 0) {
      EXPECT_LT(std::abs(r.truncation[p + 1] - r.truncation[p]), 0.5f * (mRight - mLeft));
    }
  // Where one mode suffices, the map's reconstruction beats the global M.
  PcaSettings global;
  global.fixedModes = r.globalModes;
  const PcaResult g = denoise(noisy, global);
  EXPECT_GT(r.globalModes, 2);
  EXPECT_LT(test::mse(r.frames, clean, left), test::mse(g.frames, clean, left) / 2);
}

TEST(Truncation, ImportanceBlendFollowsAlpha) {
  Frame low(3, 1), high(3, 1);
  for (float& v : high.rgb) v = 1.0f;
  const std::vector<float> m{2.0f, 5.5f, 9.0f};
  const Frame out = blendHighSamples(low, high, m, 4.0f, 7.0f);
  EXPECT_FLOAT_EQ(out.rgb[0], 0.0f);  // m <= M_min: the reconstruction
  EXPECT_FLOAT_EQ(out.rgb[3], 0.5f);  // halfway between M_min and M_max
  EXPECT_FLOAT_EQ(out.rgb[6], 1.0f);  // m >= M_max: the high-sample render
  EXPECT_EQ(needsHighSamples(m, 4.0f), (std::vector<bool>{false, true, true}));
  EXPECT_THROW(blendHighSamples(low, high, m, 7.0f, 4.0f), std::invalid_argument);
}

}  // namespace
}  // namespace tsr::temporal
