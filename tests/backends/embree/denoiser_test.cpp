// The whole-image denoiser (denoiser.hpp): on a real 8-spp render it beats
// the unfiltered image in its worst tile; at many samples it lets go of
// the image tile by tile; a checkerboard keeps its contrast (demodulation
// by albedo); a small highlight keeps its energy; a sparse field of spikes
// leaves no grid of the a-trous steps; bad input is refused.
#include "tsr/embree/denoiser.hpp"
#include "test_scenes.hpp"
#include "tsr/embree/error.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace tsr::embree::test {
namespace {

// The denoiser's input held as images.
struct Images {
  std::uint32_t w, h;
  std::vector<glm::vec3> colour, variance, albedo, normal;
  std::vector<float> depth;
  Images(std::uint32_t width, std::uint32_t height)
      : w(width),
        h(height),
        colour(w * h),
        variance(w * h),
        albedo(w * h, glm::vec3(0.5f)),
        normal(w * h, glm::vec3(0, 0, 1)),
        depth(w * h, 1.0f) {}
  explicit Images(const FrameBuffer& fb) : Images(fb.width(), fb.height()) {
    for (std::uint32_t y = 0; y < h; ++y)
      for (std::uint32_t x = 0; x < w; ++x) {
        const std::size_t i = at(x, y);
        colour[i] = fb.mean(Channel::Colour, x, y);
        variance[i] = fb.variance(Channel::Colour, x, y) / float(fb.sampleCount(x, y));
        albedo[i] = fb.albedo(x, y);
        normal[i] = fb.normal(x, y);
        depth[i] = fb.depth(x, y);
      }
  }
  std::size_t at(std::uint32_t x, std::uint32_t y) const { return std::size_t(y) * w + x; }
  DenoiseInput input() const { return {w, h, colour, variance, albedo, normal, depth}; }
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

TEST(Denoiser, EightSamplesDenoisedBeatEightUnfilteredInTheWorstTileAndLetGoWhenConverged) {
  const Images ref(cornell(1024, 99));
  const Images eight(cornell(8, 1));
  const std::vector<glm::vec3> denoised = denoise(eight.input(), DenoiseSettings{});
  const double raw = worstTile(eight.colour, ref.colour, 48, 48);
  const double filtered = worstTile(denoised, ref.colour, 48, 48);
  EXPECT_LT(filtered, 0.7 * raw) << "denoised " << filtered << ", unfiltered " << raw;

  // At 1024 spp each tile of the denoised image stays within a few percent
  // of the unfiltered one.
  const Images many(cornell(1024, 5));
  const std::vector<glm::vec3> kept = denoise(many.input(), DenoiseSettings{});
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
TEST(Denoiser, ACheckerKeepsItsContrast) {
  Images im(64, 64);
  std::mt19937 rng(3);
  std::normal_distribution<float> noise(0.0f, 1.0f);
  for (std::uint32_t y = 0; y < 64; ++y)
    for (std::uint32_t x = 0; x < 64; ++x) {
      const std::size_t i = im.at(x, y);
      const float a = ((x / 4 + y / 4) % 2) ? 0.9f : 0.1f;
      const float light = 1.0f + 0.5f * float(x) / 64.0f;
      im.albedo[i] = glm::vec3(a);
      im.colour[i] = glm::vec3(a * light * (1.0f + 0.3f * noise(rng)));
      im.variance[i] = glm::vec3(a * light * 0.3f * a * light * 0.3f);
    }
  const std::vector<glm::vec3> out = denoise(im.input(), DenoiseSettings{});
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
TEST(Denoiser, AHighlightKeepsItsEnergy) {
  Images im(48, 48);
  std::mt19937 rng(5);
  std::normal_distribution<float> noise(0.0f, 1.0f);
  double truth = 0.0;
  for (std::uint32_t y = 0; y < 48; ++y)
    for (std::uint32_t x = 0; x < 48; ++x) {
      const std::size_t i = im.at(x, y);
      const bool spot = x >= 23 && x <= 25 && y >= 23 && y <= 25;
      const float l = spot ? 10.0f : 0.5f;
      im.colour[i] = glm::vec3(l * (1.0f + 0.2f * noise(rng)));
      im.variance[i] = glm::vec3(0.04f * l * l);
      if (spot) truth += l;
    }
  const std::vector<glm::vec3> out = denoise(im.input(), DenoiseSettings{});
  double kept = 0.0;
  for (std::uint32_t y = 23; y <= 25; ++y)
    for (std::uint32_t x = 23; x <= 25; ++x) kept += out[im.at(x, y)].x;
  EXPECT_NEAR(kept, truth, 0.1 * truth);
}

// Rare bright paths on a flat wall: the autocorrelation of the result falls
// with the lag, with no peak at the a-trous steps 1, 2, 4, 8, 16.
TEST(Denoiser, PrintsNoGridOfItsSteps) {
  Images im(160, 160);
  std::mt19937 rng(21);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (std::size_t i = 0; i < im.colour.size(); ++i) {
    im.colour[i] = glm::vec3(u(rng) < 0.02f ? 50.0f : 0.0f);
    im.variance[i] = glm::vec3(12.0f);
  }
  const std::vector<glm::vec3> out = denoise(im.input(), DenoiseSettings{});
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
}

}  // namespace
}  // namespace tsr::embree::test
