// The whole-image denoiser (denoiser.hpp), each method: on a real 8-spp
// render it beats the unfiltered image in its worst tile; at many samples
// it lets go of the image tile by tile; a checkerboard keeps its contrast
// (demodulation by albedo); a small highlight keeps its energy; a sparse
// field of spikes leaves no grid (the a-trous steps, the regression's
// window); bad input is refused.
#include "tsr/embree/denoiser.hpp"
#include "test_scenes.hpp"
#include "tsr/embree/error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace tsr::embree::test {
namespace {

// The denoiser's input held as images.
struct Images {
  std::uint32_t w, h;
  std::vector<glm::vec3> colour, variance, albedo, normal, firstHalf;
  std::vector<float> depth, share;
  std::vector<glm::vec3> emitted;  // empty unless from a render
  Images(std::uint32_t width, std::uint32_t height)
      : w(width),
        h(height),
        colour(w * h),
        variance(w * h),
        albedo(w * h, glm::vec3(0.5f)),
        normal(w * h, glm::vec3(0, 0, 1)),
        firstHalf(w * h),
        depth(w * h, 1.0f),
        share(w * h, 0.5f) {}
  explicit Images(const FrameBuffer& fb) : Images(fb.width(), fb.height()) {
    for (std::uint32_t y = 0; y < h; ++y)
      for (std::uint32_t x = 0; x < w; ++x) {
        const std::size_t i = at(x, y);
        colour[i] = fb.mean(Channel::Colour, x, y);
        variance[i] = fb.variance(Channel::Colour, x, y) / float(fb.sampleCount(x, y));
        albedo[i] = fb.albedo(x, y);
        normal[i] = fb.normal(x, y);
        depth[i] = fb.depth(x, y);
        firstHalf[i] = fb.firstHalf(x, y);
        share[i] = float(fb.firstHalfCount(x, y)) / float(fb.sampleCount(x, y));
        emitted.push_back(fb.emitted(x, y));
      }
  }
  // Pixel i from two halves of its samples, each drawn by `half`; its
  // variance of the mean is set by the caller.
  template <typename Draw>
  void split(std::size_t i, Draw&& half) {
    firstHalf[i] = half();
    colour[i] = 0.5f * (firstHalf[i] + half());
  }
  std::size_t at(std::uint32_t x, std::uint32_t y) const { return std::size_t(y) * w + x; }
  DenoiseInput input() const { return {w, h, colour, variance, albedo, normal, depth, firstHalf, share, emitted}; }
};

// Mean squared error of luminance over each 8x8 tile; the worst tile's.
double worstTile(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& ref, std::uint32_t w, std::uint32_t h) {
  double worst = 0.0;
  for (std::uint32_t ty = 0; ty < h; ty += 8)
    for (std::uint32_t tx = 0; tx < w; tx += 8) {
      double sum = 0.0;
      for (std::uint32_t y = ty; y < ty + 8; ++y)
        for (std::uint32_t x = tx; x < tx + 8; ++x) {
          const double d = luminance(a[y * w + x]) - luminance(ref[y * w + x]);
          sum += d * d;
        }
      worst = std::max(worst, sum / 64.0);
    }
  return worst;
}

FrameBuffer cornell(std::uint32_t spp, std::uint64_t seed) {
  Scene scene(sharedDevice());
  const Camera camera = cornellBox(scene, 400);
  RenderSettings s;
  s.samplesPerPass = spp;
  s.seed = seed;
  s.maxDepth = 4;
  Renderer renderer(s);
  FrameBuffer fb(48, 48);
  render(renderer, scene, camera, Region::full(48, 48), fb, 1);
  return fb;
}

class DenoiserMethods : public ::testing::TestWithParam<DenoiseMethod> {
 protected:
  DenoiseSettings settings() const {
    DenoiseSettings s;
    s.method = GetParam();
    return s;
  }
};

INSTANTIATE_TEST_SUITE_P(Each, DenoiserMethods, ::testing::Values(DenoiseMethod::Regression, DenoiseMethod::Atrous),
                         [](const auto& info) {
                           return std::string(info.param == DenoiseMethod::Regression ? "Regression" : "Atrous");
                         });

TEST_P(DenoiserMethods, EightSamplesDenoisedBeatEightUnfilteredInTheWorstTileAndLetGoWhenConverged) {
  const Images ref(cornell(1024, 99));
  const Images eight(cornell(8, 1));
  const std::vector<glm::vec3> denoised = denoise(eight.input(), settings());
  const double raw = worstTile(eight.colour, ref.colour, 48, 48);
  const double filtered = worstTile(denoised, ref.colour, 48, 48);
  EXPECT_LT(filtered, 0.7 * raw) << "denoised " << filtered << ", unfiltered " << raw;

  // At 1024 spp each tile of the denoised image stays within a few percent
  // of the unfiltered one.
  const Images many(cornell(1024, 5));
  const std::vector<glm::vec3> kept = denoise(many.input(), settings());
  for (std::uint32_t ty = 0; ty < 48; ty += 8)
    for (std::uint32_t tx = 0; tx < 48; tx += 8) {
      double a = 0.0, b = 0.0;
      for (std::uint32_t y = ty; y < ty + 8; ++y)
        for (std::uint32_t x = tx; x < tx + 8; ++x) {
          a += luminance(kept[many.at(x, y)]);
          b += luminance(many.colour[many.at(x, y)]);
        }
      EXPECT_NEAR(a, b, 0.03 * b + 1e-3) << "tile at " << tx << "," << ty;
    }
}

// A 4-px checker of albedo 0.1 and 0.9 under smooth light, with noise of
// 30 % of the light: the denoised squares keep their albedo ratio.
TEST_P(DenoiserMethods, ACheckerKeepsItsContrast) {
  Images im(64, 64);
  std::mt19937 rng(3);
  std::normal_distribution<float> noise(0.0f, 1.0f);
  for (std::uint32_t y = 0; y < 64; ++y)
    for (std::uint32_t x = 0; x < 64; ++x) {
      const std::size_t i = im.at(x, y);
      const float a = ((x / 4 + y / 4) % 2) ? 0.9f : 0.1f;
      const float light = 1.0f + 0.5f * float(x) / 64.0f;
      im.albedo[i] = glm::vec3(a);
      im.split(i, [&] { return glm::vec3(a * light * (1.0f + 0.3f * std::sqrt(2.0f) * noise(rng))); });
      im.variance[i] = glm::vec3(a * light * 0.3f * a * light * 0.3f);
    }
  const std::vector<glm::vec3> out = denoise(im.input(), settings());
  double bright = 0.0, dark = 0.0, brightTruth = 0.0, darkTruth = 0.0;
  for (std::uint32_t y = 8; y < 56; ++y)
    for (std::uint32_t x = 8; x < 56; ++x) {
      const bool isBright = (x / 4 + y / 4) % 2;
      const float light = 1.0f + 0.5f * float(x) / 64.0f;
      (isBright ? bright : dark) += out[im.at(x, y)].x;
      (isBright ? brightTruth : darkTruth) += (isBright ? 0.9f : 0.1f) * light;
    }
  EXPECT_NEAR(bright / dark, brightTruth / darkTruth, 0.05 * brightTruth / darkTruth);
}

// A 3x3-pixel highlight 20 times brighter than the noisy surface around it
// (its own noise small against that step) keeps its energy.
TEST_P(DenoiserMethods, AHighlightKeepsItsEnergy) {
  Images im(48, 48);
  std::mt19937 rng(5);
  std::normal_distribution<float> noise(0.0f, 1.0f);
  double truth = 0.0;
  for (std::uint32_t y = 0; y < 48; ++y)
    for (std::uint32_t x = 0; x < 48; ++x) {
      const std::size_t i = im.at(x, y);
      const bool spot = x >= 23 && x <= 25 && y >= 23 && y <= 25;
      const float l = spot ? 10.0f : 0.5f;
      im.split(i, [&] { return glm::vec3(l * (1.0f + 0.2f * std::sqrt(2.0f) * noise(rng))); });
      im.variance[i] = glm::vec3(0.04f * l * l);
      if (spot) truth += l;
    }
  const std::vector<glm::vec3> out = denoise(im.input(), settings());
  double kept = 0.0;
  for (std::uint32_t y = 23; y <= 25; ++y)
    for (std::uint32_t x = 23; x <= 25; ++x) kept += out[im.at(x, y)].x;
  EXPECT_NEAR(kept, truth, 0.1 * truth);
}

// The path tracer's emitted part: a lamp seen directly is in it, the light
// the floor reflects is not, and it never exceeds the pixel's colour.
TEST(Denoiser, TheLampSeenDirectlyIsEmittedTheFloorIsNot) {
  Scene scene(sharedDevice());
  floorUnderLamp(scene);
  const Camera camera = Camera::lookAt({0, 2, 8}, {0, 3, 0}, {0, 1, 0}, glm::radians(60.0f), 1.0f);
  RenderSettings s;
  s.samplesPerPass = 4;
  s.seed = 3;
  Renderer renderer(s);
  FrameBuffer fb(32, 32);
  render(renderer, scene, camera, Region::full(32, 32), fb, 1);
  std::size_t lamp = 0, lit = 0;
  for (std::uint32_t y = 0; y < fb.height(); ++y)
    for (std::uint32_t x = 0; x < fb.width(); ++x) {
      const glm::vec3 e = fb.emitted(x, y), c = fb.mean(Channel::Colour, x, y);
      lamp += luminance(e) > 0.0f;
      lit += luminance(c) > 0.0f && luminance(e) == 0.0f;
      EXPECT_LE(luminance(e), luminance(c) * 1.0001f + 1e-6f) << x << "," << y;
    }
  EXPECT_GT(lamp, 4u) << "the lamp is seen";
  EXPECT_GT(lit, fb.width() * fb.height() / 4) << "the floor reflects light";
}

// A lamp one pixel tall, seen directly, in a noisy ceiling: given as
// emission it keeps its brightness and does not glow over the rows beside
// it.
TEST_P(DenoiserMethods, EmissionSeenDirectlyStaysAsItIs) {
  Images im(48, 48);
  im.emitted.assign(im.colour.size(), glm::vec3(0.0f));
  std::mt19937 rng(9);
  std::normal_distribution<float> noise(0.0f, 1.0f);
  for (std::uint32_t y = 0; y < 48; ++y)
    for (std::uint32_t x = 0; x < 48; ++x) {
      const std::size_t i = im.at(x, y);
      const bool lamp = y == 24 && x >= 8 && x < 40;
      const float lit = 0.5f;
      im.split(i, [&] { return glm::vec3(lit * (1.0f + 0.4f * std::sqrt(2.0f) * noise(rng))); });
      im.variance[i] = glm::vec3(0.04f * lit * lit);
      if (lamp) {
        im.emitted[i] = glm::vec3(20.0f);
        im.colour[i] += im.emitted[i];
      }
    }
  const std::vector<glm::vec3> out = denoise(im.input(), settings());
  double lamp = 0.0, beside = 0.0;
  for (std::uint32_t x = 12; x < 36; ++x) {
    lamp += out[im.at(x, 24)].x / 24.0;
    beside += (out[im.at(x, 23)].x + out[im.at(x, 25)].x) / 48.0;
  }
  EXPECT_NEAR(lamp, 20.5, 0.5);
  EXPECT_NEAR(beside, 0.5, 0.1) << "the lamp glows over its neighbours";
}

// Rare bright paths on a flat wall (each half of a pixel's samples finds one
// with chance 1 %): the autocorrelation of the result falls with the lag,
// with no peak at the a-trous steps 1, 2, 4, 8, 16.
TEST_P(DenoiserMethods, PrintsNoGridOfItsSteps) {
  Images im(160, 160);
  std::mt19937 rng(21);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (std::size_t i = 0; i < im.colour.size(); ++i) {
    im.split(i, [&] { return glm::vec3(u(rng) < 0.01f ? 100.0f : 0.0f); });
    im.variance[i] = glm::vec3(49.5f);  // 100^2 * 0.01 * 0.99 per half, over 2
  }
  const std::vector<glm::vec3> out = denoise(im.input(), settings());
  double mean = 0;
  for (const auto& l : out) mean += l.x;
  mean /= double(out.size());
  auto correlation = [&](int lag) {
    double sum = 0, norm = 0;
    for (std::uint32_t y = 24; y < 120; ++y)
      for (std::uint32_t x = 24; x < 120; ++x) {
        const double a = out[im.at(x, y)].x - mean;
        sum += a * (out[im.at(x + lag, y)].x - mean) + a * (out[im.at(x, y + lag)].x - mean);
        norm += 2 * a * a;
      }
    return sum / norm;
  };
  for (int lag : {2, 4, 8, 16}) {
    const double before = correlation(lag - 1), at = correlation(lag), after = correlation(lag + 1);
    EXPECT_LT(at, std::max(before, after) + 0.02)
        << "autocorrelation peaks at lag " << lag << ": " << before << ", " << at << ", " << after;
  }
}

// Images smaller than the window and the patches: every pixel comes back
// finite and, on a flat noiseless image, unchanged.
TEST_P(DenoiserMethods, ImagesSmallerThanTheWindowAreDenoised) {
  for (const auto& [w, h] : {std::pair{1u, 1u}, std::pair{3u, 2u}, std::pair{40u, 1u}}) {
    Images im(w, h);
    for (std::size_t i = 0; i < im.colour.size(); ++i) im.split(i, [] { return glm::vec3(0.25f); });
    const std::vector<glm::vec3> out = denoise(im.input(), settings());
    ASSERT_EQ(out.size(), im.colour.size());
    for (const glm::vec3& c : out) EXPECT_NEAR(c.y, 0.25f, 1e-4f) << w << "x" << h;
  }
}

TEST(Denoiser, RefusesImagesOfOtherSizesAndBadSettings) {
  Images im(8, 8);
  DenoiseInput in = im.input();
  in.albedo = in.albedo.subspan(1);
  EXPECT_THROW(denoise(in, DenoiseSettings{}), Error);
  DenoiseSettings s;
  s.levels = 0;
  EXPECT_THROW(denoise(im.input(), s), Error);
  s = DenoiseSettings{};
  s.sigmaLuminance = 0.0f;
  EXPECT_THROW(denoise(im.input(), s), Error);
  s = DenoiseSettings{};
  s.radius = 0;
  EXPECT_THROW(denoise(im.input(), s), Error);
  s = DenoiseSettings{};
  s.patchRadius = 9;
  EXPECT_THROW(denoise(im.input(), s), Error);
  // The regression needs the halves; the a-trous method does not.
  in = im.input();
  in.firstHalf = {};
  EXPECT_THROW(denoise(in, DenoiseSettings{}), Error);
  in.firstHalfShare = {};
  s = DenoiseSettings{};
  s.method = DenoiseMethod::Atrous;
  EXPECT_NO_THROW(denoise(in, s));
}

}  // namespace
}  // namespace tsr::embree::test
