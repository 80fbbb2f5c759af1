// The path sampler (sampler.hpp): the first 2^k samples of a pixel are
// stratified in every 2-D set at every k (one point per elementary
// interval), sets are independent of each other, values are a pure
// function of their arguments, the independent sampler is the old white
// noise bit for bit, and on a lit floor the stratified samples give a
// lower error than white noise at the same sample count.
#include "tsr/embree/sampler.hpp"
#include "test_scenes.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <vector>

namespace tsr::embree::test {
namespace {

// Draws `sets` 2-D sets of sample `index` in a pixel.
std::vector<glm::vec2> draws(SamplerKind kind, std::uint64_t key, std::uint32_t index, int sets) {
  Sampler s(kind, key, index);
  std::vector<glm::vec2> out;
  for (int i = 0; i < sets; ++i) out.push_back(s.uniform2());
  return out;
}

// Whether n = 2^k points fall one per elementary interval of every shape
// 2^a x 2^(k-a).
bool isNet(const std::vector<glm::vec2>& points) {
  const auto n = std::uint32_t(points.size());
  const int k = std::countr_zero(n);
  for (int a = 0; a <= k; ++a) {
    const std::uint32_t cols = 1u << a, rows = 1u << (k - a);
    std::vector<int> count(n, 0);
    for (const glm::vec2& p : points) {
      const auto cx = std::uint32_t(p.x * float(cols)), cy = std::uint32_t(p.y * float(rows));
      if (cx >= cols || cy >= rows || ++count[cy * cols + cx] > 1) return false;
    }
  }
  return true;
}

TEST(Sampler, EveryPowerOfTwoPrefixIsANetInEverySet) {
  constexpr int kSets = 12;
  for (std::uint64_t pixel : {Rng::pixelKey(0, 0, 0), Rng::pixelKey(0, 17, 3), Rng::pixelKey(42, 511, 511)}) {
    std::vector<std::vector<glm::vec2>> bySet(kSets);
    for (std::uint32_t i = 0; i < 1024; ++i) {
      const auto d = draws(SamplerKind::Sobol, pixel, i, kSets);
      for (int s = 0; s < kSets; ++s) bySet[s].push_back(d[s]);
      if (!std::has_single_bit(i + 1)) continue;
      for (int s = 0; s < kSets; ++s) ASSERT_TRUE(isNet(bySet[s])) << "set " << s << ", first " << i + 1 << " samples";
    }
  }
}

TEST(Sampler, OneDimensionalDrawsAreStratified) {
  const std::uint64_t pixel = Rng::pixelKey(5, 9, 9);
  for (std::uint32_t n : {1u, 2u, 8u, 64u, 256u}) {
    for (int set = 0; set < 6; ++set) {
      std::vector<int> count(n, 0);
      for (std::uint32_t i = 0; i < n; ++i) {
        Sampler s(SamplerKind::Sobol, pixel, i);
        float u = 0.0f;
        for (int d = 0; d <= set; ++d) u = s.uniform();
        ++count[std::uint32_t(u * float(n))];
      }
      for (int c : count) ASSERT_EQ(c, 1) << n << " samples, set " << set;
    }
  }
}

// Two sets are independent: their joint 8x8 histogram over 4096 samples is
// uniform by chi-squared (63 degrees of freedom; 110 is p ~ 0.0002). A set
// correlated with another (the same scramble twice) fails by far.
TEST(Sampler, SetsAreIndependentOfEachOther) {
  const std::uint64_t pixel = Rng::pixelKey(1, 2, 3);
  for (int pair = 0; pair < 4; ++pair) {
    std::vector<int> bins(64, 0);
    for (std::uint32_t i = 0; i < 4096; ++i) {
      const auto d = draws(SamplerKind::Sobol, pixel, i, 4);
      const glm::vec2 a = d[pair % 2], b = d[2 + pair / 2];
      ++bins[std::uint32_t(a.x * 8) * 8 + std::uint32_t(b.y * 8)];
    }
    double chi2 = 0.0;
    for (int c : bins) chi2 += (c - 64.0) * (c - 64.0) / 64.0;
    EXPECT_LT(chi2, 110.0) << "pair " << pair;
  }
}

TEST(Sampler, PixelsGetDifferentPatterns) {
  const auto a = draws(SamplerKind::Sobol, Rng::pixelKey(0, 0, 0), 0, 4);
  const auto b = draws(SamplerKind::Sobol, Rng::pixelKey(0, 1, 0), 0, 4);
  const auto c = draws(SamplerKind::Sobol, Rng::pixelKey(1, 0, 0), 0, 4);
  const auto again = draws(SamplerKind::Sobol, Rng::pixelKey(0, 0, 0), 0, 4);
  EXPECT_NE(a, b);
  EXPECT_NE(a, c);
  EXPECT_EQ(a, again);
}

TEST(Sampler, IndependentIsTheCounterHashStream) {
  const std::uint64_t key = Rng::pixelKey(3, 4, 5);
  Rng rng(key, 6);
  Sampler s(SamplerKind::Independent, key, 6);
  for (int i = 0; i < 8; ++i) {
    const float a = rng.uniform();
    const glm::vec2 b = rng.uniform2();
    EXPECT_EQ(s.uniform(), a);
    EXPECT_EQ(s.uniform2(), b);
  }
}

// Direct light of a 2x2 lamp on a floor at 4 spp: the stratified sampler's
// error against a 1024-spp image is well below white noise's, and both
// converge to the same image (no bias: means agree within their noise).
FrameBuffer lampOnFloor(SamplerKind kind, std::uint32_t spp, std::uint64_t seed) {
  Scene scene(sharedDevice());
  floorUnderLamp(scene);
  RenderSettings s;
  s.maxDepth = 1;
  s.samplesPerPass = spp;
  s.seed = seed;
  s.sampler = kind;
  Renderer renderer(s);
  constexpr std::uint32_t kSize = 32;
  FrameBuffer fb(kSize, kSize);
  const Camera cam = Camera::lookAt({0, 3, 6}, {0, 0, 0}, {0, 1, 0}, glm::radians(60.0f), 1.0f);
  render(renderer, scene, cam, Region::full(kSize, kSize), fb, 1);
  return fb;
}

double meanSquaredError(const FrameBuffer& a, const FrameBuffer& ref) {
  double sum = 0.0;
  for (std::uint32_t y = 0; y < a.height(); ++y)
    for (std::uint32_t x = 0; x < a.width(); ++x) {
      const double d = luminance(a.mean(Channel::Colour, x, y)) - luminance(ref.mean(Channel::Colour, x, y));
      sum += d * d;
    }
  return sum / double(a.width() * a.height());
}

TEST(Sampler, StratifiedDirectLightHasLessErrorAndTheSameMean) {
  const FrameBuffer ref = lampOnFloor(SamplerKind::Independent, 1024, 77);
  const double sobol = meanSquaredError(lampOnFloor(SamplerKind::Sobol, 4, 1), ref);
  const double white = meanSquaredError(lampOnFloor(SamplerKind::Independent, 4, 1), ref);
  EXPECT_LT(sobol, 0.6 * white) << "sobol " << sobol << ", independent " << white;

  const FrameBuffer a = lampOnFloor(SamplerKind::Sobol, 256, 3);
  const double diff = luminance(meanColour(a)) - luminance(meanColour(ref));
  const double se = std::hypot(meanStandardError(a), meanStandardError(ref));
  EXPECT_LT(std::abs(diff), 4.0 * se + 1e-6)
      << "sobol mean " << luminance(meanColour(a)) << ", reference " << luminance(meanColour(ref));
}

}  // namespace
}  // namespace tsr::embree::test
