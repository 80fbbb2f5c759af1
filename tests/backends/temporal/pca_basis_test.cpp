// The PCA basis of a frame stack: exact with every mode, nested truncations,
// the fractional truncation as the paper's interpolation, typed errors.
#include <gtest/gtest.h>

#include "synthetic_sequence.hpp"
#include "tsr/temporal/pca_basis.hpp"

namespace tsr::temporal {
namespace {

std::vector<Frame> randomStack(int frames, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 2.0f);
  return test::sequence(frames, 9, 7, [&](std::uint32_t, std::uint32_t, int) { return u(rng); });
}

TEST(PcaBasis, AllModesReproduceTheInput) {
  for (int frames : {1, 2, 5, 12}) {
    const auto input = randomStack(frames, 7u + unsigned(frames));
    const PcaBasis basis(input);
    ASSERT_EQ(basis.modes(), frames);
    for (int t = 0; t < frames; ++t) {
      const Frame back = basis.reconstruct(t, frames);
      for (std::size_t i = 0; i < back.rgb.size(); ++i)
        EXPECT_NEAR(back.rgb[i], input[size_t(t)].rgb[i], 1e-4f) << frames;
    }
  }
}

TEST(PcaBasis, UnexplainedEnergyFallsToZeroWithEveryMode) {
  const PcaBasis basis(randomStack(8, 3));
  const auto left = basis.unexplained();
  ASSERT_EQ(left.size(), 9u);
  EXPECT_DOUBLE_EQ(left.front(), 1.0);
  EXPECT_NEAR(left.back(), 0.0, 1e-9);
  for (std::size_t x = 1; x < left.size(); ++x) EXPECT_LE(left[x], left[x - 1] + 1e-12);
  // The error of a truncated reconstruction is exactly the energy left.
  const auto input = randomStack(8, 3);
  double total = 0, error = 0;
  for (int t = 0; t < 8; ++t) {
    const Frame r = basis.reconstruct(t, 3);
    for (std::size_t i = 0; i < r.rgb.size(); ++i) {
      total += double(input[size_t(t)].rgb[i]) * input[size_t(t)].rgb[i];
      error += (double(r.rgb[i]) - input[size_t(t)].rgb[i]) * (double(r.rgb[i]) - input[size_t(t)].rgb[i]);
    }
  }
  EXPECT_NEAR(error / total, left[3], 1e-4);
}

TEST(PcaBasis, AScaledImageNeedsTheMeanAndOneMode) {
  // A fixed image whose brightness changes: the mean and one mode.
  const auto input = test::sequence(10, 8, 8, [](std::uint32_t x, std::uint32_t y, int t) {
    return (1.0f + 0.1f * float(x) + 0.05f * float(y)) * (1.0f + 0.3f * std::sin(float(t)));
  });
  const PcaBasis basis(input);
  EXPECT_GT(basis.unexplained()[1], 1e-4);
  EXPECT_NEAR(basis.unexplained()[2], 0.0, 1e-6);
  for (int t = 0; t < 10; ++t) {
    const Frame r = basis.reconstruct(t, 2);
    for (std::size_t i = 0; i < r.rgb.size(); ++i) EXPECT_NEAR(r.rgb[i], input[size_t(t)].rgb[i], 1e-4f);
  }
}

TEST(PcaBasis, AStaticSequenceIsItsMean) {
  std::vector<Frame> input =
      test::sequence(6, 5, 4, [](std::uint32_t x, std::uint32_t y, int) { return float(x + 2 * y); });
  const PcaBasis basis(input);
  EXPECT_NEAR(basis.unexplained()[1], 0.0, 1e-9);
  const Frame r = basis.reconstruct(3, 1);
  for (std::size_t i = 0; i < r.rgb.size(); ++i) EXPECT_NEAR(r.rgb[i], input[3].rgb[i], 1e-5f);
}

TEST(PcaBasis, FractionalTruncationInterpolatesNeighbouringReconstructions) {
  const PcaBasis basis(randomStack(6, 11));
  const Frame two = basis.reconstruct(4, 2), three = basis.reconstruct(4, 3);
  const Frame between = basis.reconstruct(4, std::vector<float>(9 * 7, 2.7f));
  for (std::size_t i = 0; i < between.rgb.size(); ++i)
    EXPECT_NEAR(between.rgb[i], 0.3f * two.rgb[i] + 0.7f * three.rgb[i], 1e-4f);
}

TEST(PcaBasis, PerPixelEnergyMatchesTheGlobalOneForAUniformStack) {
  const auto input = test::sequence(5, 4, 4, [](std::uint32_t, std::uint32_t, int t) { return 1.0f + float(t % 2); });
  const PcaBasis basis(input);
  const auto global = basis.unexplained(), pixel = basis.pixelUnexplained(5);
  for (std::size_t x = 0; x < global.size(); ++x) EXPECT_NEAR(pixel[x], global[x], 1e-5);
}

TEST(PcaBasis, RefusesInconsistentStacks) {
  EXPECT_THROW(PcaBasis(std::vector<Frame>{}), std::invalid_argument);
  std::vector<Frame> mixed{Frame(4, 4), Frame(4, 5)};
  EXPECT_THROW(PcaBasis{mixed}, std::invalid_argument);
  std::vector<Frame> nan{Frame(2, 2)};
  nan[0].rgb[3] = std::nanf("");
  EXPECT_THROW(PcaBasis{nan}, std::invalid_argument);
  const PcaBasis ok(randomStack(3, 1));
  EXPECT_THROW(ok.reconstruct(3, 1), std::out_of_range);
  EXPECT_THROW(ok.reconstruct(0, 4), std::out_of_range);
}

}  // namespace
}  // namespace tsr::temporal
