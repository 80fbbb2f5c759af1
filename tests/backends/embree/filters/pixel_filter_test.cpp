// Properties of the pixel filter (Schwenk 2013, ch. 3) on synthetic images.
#include "tsr/embree/pixel_filter.hpp"
#include "tsr/embree/error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <vector>

namespace {

using namespace tsr::embree;
using glm::vec3;

constexpr float kInf = std::numeric_limits<float>::infinity();

// Owns the buffers behind a PixelFilterInput.
struct Images {
  std::uint32_t w, h;
  std::vector<vec3> lu, var, llv, colour;
  std::vector<float> depth;
  std::vector<float> spread;  // empty: no range spread
  std::uint32_t samples = 4;

  Images(std::uint32_t width, std::uint32_t height)
      : w(width),
        h(height),
        lu(w * h, vec3(0.5f)),
        var(w * h, vec3(0.01f)),
        llv(w * h, vec3(0.0f)),
        colour(w * h, vec3(0.5f)),
        depth(w * h, 1.0f) {}

  std::size_t at(std::uint32_t x, std::uint32_t y) const { return std::size_t(y) * w + x; }
  void each(const std::function<void(std::uint32_t, std::uint32_t, std::size_t)>& f) {
    for (std::uint32_t y = 0; y < h; ++y)
      for (std::uint32_t x = 0; x < w; ++x) f(x, y, at(x, y));
  }
  void addNoise(float sd, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> n(0.0f, sd);
    for (auto& l : lu) l += vec3(n(rng));  // grey noise: the same offset in every channel
    for (auto& v : var) v = vec3(sd * sd);
  }
  PixelFilterInput input() const { return {w, h, lu, var, llv, colour, depth, samples, spread}; }
};

PixelFilterSettings settingsFor(FilterKernel k) {
  PixelFilterSettings s;
  s.kernel = k;
  return s;
}

const FilterKernel kKernels[] = {FilterKernel::Bilateral, FilterKernel::Separable, FilterKernel::Atrous};

const char* name(FilterKernel k) {
  return k == FilterKernel::Bilateral ? "bilateral" : k == FilterKernel::Separable ? "separable" : "atrous";
}

// Variance of one channel over the pixels at least `border` from the edge.
double interiorVariance(const std::vector<vec3>& img, std::uint32_t w, std::uint32_t h, std::uint32_t border) {
  double s = 0, s2 = 0, n = 0;
  for (std::uint32_t y = border; y < h - border; ++y)
    for (std::uint32_t x = border; x < w - border; ++x) {
      const double v = img[std::size_t(y) * w + x].x;
      s += v;
      s2 += v * v;
      n += 1;
    }
  return s2 / n - (s / n) * (s / n);
}

double interiorMean(const std::vector<float>& img, std::uint32_t w, std::uint32_t h, std::uint32_t border) {
  double s = 0, n = 0;
  for (std::uint32_t y = border; y < h - border; ++y)
    for (std::uint32_t x = border; x < w - border; ++x) s += img[std::size_t(y) * w + x], n += 1;
  return s / n;
}

// ------------------------------------------------------------ blend factor

TEST(PixelFilterBlend, CasesOfEquation313) {
  EXPECT_EQ(blendFactor(0.005f, 0.001f, 0.01f), 1.0f);  // u <= t: unfiltered already good enough
  EXPECT_EQ(blendFactor(0.01f, 0.001f, 0.01f), 1.0f);   // u == t
  EXPECT_EQ(blendFactor(1.0f, 0.5f, 0.01f), 0.0f);      // tu + tf - uf < 0: even Lf is too noisy
  EXPECT_EQ(blendFactor(0.0f, 0.0f, 0.01f), 1.0f);      // u = f = 0: case 2
  EXPECT_EQ(blendFactor(0.0f, 0.0f, 0.0f), 1.0f);
  EXPECT_EQ(blendFactor(0.5f, 0.1f, 0.0f), 0.0f);  // t = 0, u > 0: case 1
  EXPECT_EQ(blendFactor(0.5f, 0.0f, 0.0f), 0.0f);
  // Case 3 is 3.12.
  const float u = 0.02f, f = 0.002f, t = 0.01f;
  EXPECT_NEAR(blendFactor(u, f, t), (f + std::sqrt(t * u + t * f - u * f)) / (u + f), 1e-6f);
  // And s reaches the threshold: s^2 u + (1-s)^2 f = t (no covariance).
  const float s = blendFactor(u, f, t);
  EXPECT_NEAR(s * s * u + (1 - s) * (1 - s) * f, t, 1e-6f);
}

TEST(PixelFilterBlend, MonotoneDecreasingBetweenTheTwoPoints) {
  // Appendix 3.A: t = 1, f = 0.1 u; (a) at u = t, (b) where tu + tf - uf = 0, u = 11.
  const float t = 1.0f;
  EXPECT_NEAR(blendFactor(1.0001f, 0.10001f, t), 1.0f, 1e-3f);  // continuous at (a)
  float previous = 1.0f;
  for (float u = 1.05f; u < 10.95f; u += 0.05f) {
    const float s = blendFactor(u, 0.1f * u, t);
    EXPECT_LT(s, previous) << "u = " << u;
    EXPECT_GT(s, 0.0f);
    previous = s;
  }
  EXPECT_EQ(blendFactor(11.05f, 1.105f, t), 0.0f);  // past (b)
}

TEST(PixelFilterBlend, NonFiniteVarianceUsesTheFilteredValue) {
  EXPECT_EQ(blendFactor(kInf, 1.0f, 0.01f), 0.0f);
  EXPECT_EQ(blendFactor(std::nanf(""), 1.0f, 0.01f), 0.0f);
}

TEST(PixelFilterBlend, BlendFactorGoesToOneAsVarianceShrinks) {
  Images im(48, 48);
  im.addNoise(0.2f, 1);
  const PixelFilterSettings s = settingsFor(FilterKernel::Bilateral);
  double previous = -1;
  for (float scale : {1.0f, 1e-1f, 1e-2f, 1e-3f, 1e-5f}) {
    Images scaled = im;
    for (auto& v : scaled.var) v *= scale;
    const FilteredBuffer fb = filterHighVariance(scaled.input(), s);
    const BlendResult b = blend(scaled.input(), fb, s);
    double mean = 0;
    for (float f : b.blendFactor) mean += f;
    mean /= double(b.blendFactor.size());
    EXPECT_GE(mean, previous);
    previous = mean;
  }
  EXPECT_EQ(previous, 1.0);
}

TEST(PixelFilterBlend, OlderFilteredBufferIsRescaledToTheCurrentSampleCount) {
  Images im(16, 16);
  im.addNoise(0.2f, 2);
  PixelFilterSettings s = settingsFor(FilterKernel::Bilateral);
  s.threshold = 0.02f;
  const FilteredBuffer fb = filterHighVariance(im.input(), s);  // at n = 4
  Images later = im;
  later.samples = 4000;  // Var[Lu] is 1000 times smaller now
  const BlendResult b = blend(later.input(), fb, s);
  for (float f : b.blendFactor) EXPECT_EQ(f, 1.0f);
}

TEST(PixelFilterBlend, SpikeRemovalClampsToHalfAndTwiceTheFilteredValueWhileBlending) {
  Images im(33, 33);
  im.lu.assign(im.lu.size(), vec3(1.0f));
  im.var.assign(im.var.size(), vec3(0.05f));  // u above t: the filtered buffer is blended in (s < 1)
  const std::size_t spike = im.at(16, 16), dark = im.at(5, 5);
  im.lu[spike] = vec3(100.0f);
  im.lu[dark] = vec3(0.0f);
  PixelFilterSettings s = settingsFor(FilterKernel::Bilateral);
  const FilteredBuffer fb = filterHighVariance(im.input(), s);
  const BlendResult plain = blend(im.input(), fb, s);
  s.spikeRemoval = true;
  const BlendResult clamped = blend(im.input(), fb, s);
  for (std::size_t i : {spike, dark}) {
    const float k = clamped.blendFactor[i];
    ASSERT_LT(k, 1.0f);
    const vec3 lu = i == spike ? 2.0f * fb.radiance[i] : 0.5f * fb.radiance[i];
    EXPECT_NEAR(clamped.radiance[i].x, k * lu.x + (1 - k) * fb.radiance[i].x, 1e-4f);
  }
  EXPECT_LT(clamped.radiance[spike].x, plain.radiance[spike].x);
  EXPECT_GT(clamped.radiance[dark].x, plain.radiance[dark].x);
}

TEST(PixelFilterBlend, SpikeRemovalWidensAsSamplesGrow) {
  // The same spike at 8 and at 512 spp: clamped to 2 Lf, then to 16 Lf
  // (2 sqrt(n/8)), so the clamp's bias fades as the image converges.
  Images im(33, 33);
  im.lu.assign(im.lu.size(), vec3(1.0f));
  im.var.assign(im.var.size(), vec3(0.05f));
  const std::size_t spike = im.at(16, 16);
  im.lu[spike] = vec3(100.0f);
  PixelFilterSettings s = settingsFor(FilterKernel::Bilateral);
  s.spikeRemoval = true;
  for (std::uint32_t n : {8u, 512u}) {
    im.samples = n;
    const FilteredBuffer fb = filterHighVariance(im.input(), s);
    const BlendResult b = blend(im.input(), fb, s);
    const float k = b.blendFactor[spike], bound = n == 8 ? 2.0f : 16.0f;
    ASSERT_LT(k, 1.0f) << n;
    EXPECT_NEAR(b.radiance[spike].x, k * bound * fb.radiance[spike].x + (1 - k) * fb.radiance[spike].x, 1e-3f) << n;
  }
}

TEST(PixelFilterBlend, SpikeRemovalLetsGoOnceTheUnfilteredPixelMeetsTheThreshold) {
  // s = 1: the pixel is shown as it is, so the clamp adds no bias to a
  // converged image (consistency).
  Images im(33, 33);
  im.lu.assign(im.lu.size(), vec3(1.0f));
  im.var.assign(im.var.size(), vec3(1e-9f));
  const std::size_t spike = im.at(16, 16);
  im.lu[spike] = vec3(100.0f);
  PixelFilterSettings s = settingsFor(FilterKernel::Bilateral);
  s.spikeRemoval = true;
  const FilteredBuffer fb = filterHighVariance(im.input(), s);
  const BlendResult b = blend(im.input(), fb, s);
  EXPECT_EQ(b.blendFactor[spike], 1.0f);
  EXPECT_EQ(b.radiance[spike], vec3(100.0f));
}

TEST(PixelFilterBlend, FinalPixelIsLowVariancePlusBlend) {
  Images im(8, 8);
  im.addNoise(0.3f, 3);
  for (auto& l : im.llv) l = vec3(0.25f, 0.5f, 0.75f);
  const PixelFilterSettings s = settingsFor(FilterKernel::Bilateral);
  const FilteredBuffer fb = filterHighVariance(im.input(), s);
  const BlendResult b = blend(im.input(), fb, s);
  for (std::size_t i = 0; i < im.lu.size(); ++i) {
    const float k = b.blendFactor[i];
    const vec3 want = im.llv[i] + k * im.lu[i] + (1 - k) * fb.radiance[i];
    EXPECT_NEAR(b.radiance[i].y, want.y, 1e-5f);
  }
}

TEST(PixelFilterSchedule, EveryPowerOfTwoFromFour) {
  for (std::uint32_t f : {0u, 1u, 2u, 3u, 5u, 6u, 7u, 9u, 12u, 24u, 100u}) EXPECT_FALSE(isFilterFrame(f)) << f;
  for (std::uint32_t f : {4u, 8u, 16u, 32u, 1024u, 1u << 31}) EXPECT_TRUE(isFilterFrame(f)) << f;
}

TEST(PixelFilterInputCheck, WrongSizesAndSettingsThrow) {
  Images im(4, 4);
  PixelFilterInput in = im.input();
  in.rangeDepth = in.rangeDepth.subspan(1);
  EXPECT_THROW(filterHighVariance(in, {}), Error);
  PixelFilterSettings s;
  s.sigmaS = 0.0f;
  EXPECT_THROW(filterHighVariance(im.input(), s), Error);
  s = {};
  s.sigmaC = 0.0f;
  EXPECT_THROW(filterHighVariance(im.input(), s), Error);
  s = {};
  s.iterations = 0;
  EXPECT_THROW(filterHighVariance(im.input(), s), Error);
  // Absurd but finite range values are clamped, not propagated as NaN.
  Images huge(4, 4);
  huge.colour[3] = vec3(1e30f);
  huge.depth[5] = -1e30f;
  huge.lu[7] = vec3(std::nanf(""));
  for (FilterKernel k : kKernels)
    for (const vec3& l : filterHighVariance(huge.input(), settingsFor(k)).radiance) EXPECT_TRUE(std::isfinite(l.x));
  const FilteredBuffer fb = filterHighVariance(im.input(), {});
  Images other(5, 4);
  EXPECT_THROW(blend(other.input(), fb, {}), Error);
}

// ------------------------------------------------------------ filter

TEST(PixelFilter, ConstantImageIsPreservedExactly) {
  Images im(40, 30);
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  im.each([&](std::uint32_t, std::uint32_t, std::size_t i) {
    im.colour[i] = vec3(u(rng), u(rng), u(rng));
    im.depth[i] = u(rng) < 0.1f ? kInf : 1.0f + 5.0f * u(rng);
    im.lu[i] = vec3(0.3f, 0.6f, 0.9f);
    im.var[i] = vec3(0.02f);
  });
  for (FilterKernel k : kKernels)
    for (bool extras : {false, true}) {
      PixelFilterSettings s = settingsFor(k);
      s.sigmaC = 0.5f;  // let the random range colours mix
      s.adaptiveWidth = s.antialiasRecovery = extras;
      const FilteredBuffer fb = filterHighVariance(im.input(), s);
      for (std::size_t i = 0; i < im.lu.size(); ++i) {
        ASSERT_EQ(fb.radiance[i], im.lu[i]) << name(k) << " pixel " << i;
        ASSERT_EQ(fb.variance[i], luminance(vec3(0.02f))) << name(k);
      }
    }
}

// A step in the range buffer (colour, depth or background) stays a step.
void expectStepKept(Images& im, const char* what) {
  im.each([&](std::uint32_t x, std::uint32_t, std::size_t i) { im.lu[i] = vec3(x < im.w / 2 ? 1.0f : 3.0f); });
  for (FilterKernel k : kKernels)
    for (bool aa : {false, true}) {
      PixelFilterSettings s = settingsFor(k);
      s.antialiasRecovery = aa;
      const FilteredBuffer fb = filterHighVariance(im.input(), s);
      im.each([&](std::uint32_t x, std::uint32_t, std::size_t i) {
        ASSERT_NEAR(fb.radiance[i].x, x < im.w / 2 ? 1.0f : 3.0f, 1e-4f) << what << " " << name(k) << " x=" << x;
      });
    }
}

TEST(PixelFilter, DoesNotBlurAcrossAColourEdge) {
  Images im(40, 24);
  im.each([&](std::uint32_t x, std::uint32_t, std::size_t i) { im.colour[i] = vec3(x < im.w / 2 ? 0.2f : 0.8f); });
  expectStepKept(im, "colour");
}

TEST(PixelFilter, DoesNotBlurAcrossADepthEdge) {
  Images im(40, 24);
  im.each([&](std::uint32_t x, std::uint32_t, std::size_t i) { im.depth[i] = x < im.w / 2 ? 1.0f : 10.0f; });
  expectStepKept(im, "depth");
}

TEST(PixelFilter, BackgroundOnlyGathersBackground) {
  Images im(40, 24);
  im.each([&](std::uint32_t x, std::uint32_t, std::size_t i) { im.depth[i] = x < im.w / 2 ? 1.0f : kInf; });
  expectStepKept(im, "background");
  // ... but background pixels do gather each other.
  Images bg(40, 40);
  bg.depth.assign(bg.depth.size(), kInf);
  bg.addNoise(0.1f, 5);
  const FilteredBuffer fb = filterHighVariance(bg.input(), settingsFor(FilterKernel::Bilateral));
  EXPECT_LT(fb.reduction[bg.at(20, 20)], 0.01f);
}

TEST(PixelFilter, ReductionIsAtMostOneAndPositive) {
  Images im(48, 40);
  std::mt19937 rng(6);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  im.each([&](std::uint32_t, std::uint32_t, std::size_t i) {
    im.colour[i] = vec3(u(rng) < 0.5f ? 0.2f : 0.7f, u(rng), 0.5f);
    im.depth[i] = 1.0f + u(rng);
  });
  im.addNoise(0.3f, 7);
  for (FilterKernel k : kKernels)
    for (bool extras : {false, true}) {
      PixelFilterSettings s = settingsFor(k);
      s.sigmaC = 0.1f;
      s.adaptiveWidth = s.antialiasRecovery = extras;
      const FilteredBuffer fb = filterHighVariance(im.input(), s);
      for (float r : fb.reduction) {
        ASSERT_GT(r, 0.0f) << name(k);
        ASSERT_LE(r, 1.0f) << name(k);
      }
    }
}

TEST(PixelFilter, ReductionIsOneOverNForABoxLikeKernel) {
  // sigmaS far wider than the image and a constant range: every weight ~1.
  Images im(8, 6);
  for (FilterKernel k : {FilterKernel::Bilateral, FilterKernel::Separable}) {
    PixelFilterSettings s = settingsFor(k);
    s.sigmaS = 1000.0f;
    const FilteredBuffer fb = filterHighVariance(im.input(), s);
    // Brute force is exact; the separable r comes from the composite kernel's
    // moments through a Gaussian-shape model, within 5% of 1/N for boxes.
    const float tol = k == FilterKernel::Bilateral ? 1e-3f : 0.05f;
    for (float r : fb.reduction) ASSERT_NEAR(r * 48.0f, 1.0f, tol) << name(k);
  }
}

TEST(PixelFilter, FastKernelsEstimateTheBruteForceReduction) {
  Images im(96, 96);
  PixelFilterSettings s = settingsFor(FilterKernel::Bilateral);
  s.sigmaS = 4.0f;
  const FilteredBuffer exact = filterHighVariance(im.input(), s);
  const double rExact = interiorMean(exact.reduction, im.w, im.h, 30);
  EXPECT_NEAR(rExact, 1.0 / (4.0 * M_PI * 16.0), 0.1 * rExact);
  for (FilterKernel k : {FilterKernel::Separable, FilterKernel::Atrous}) {
    s.kernel = k;
    const FilteredBuffer fb = filterHighVariance(im.input(), s);
    const double ratio = interiorMean(fb.reduction, im.w, im.h, 30) / rExact;
    EXPECT_NEAR(ratio, 1.0, 0.15) << name(k);
    std::printf("%s r / brute-force r = %.3f (brute-force r = %.5f)\n", name(k), ratio, rExact);
  }
}

TEST(PixelFilter, WhiteNoiseVarianceDropsByAboutR) {
  Images im(160, 160);
  im.lu.assign(im.lu.size(), vec3(1.0f));
  im.addNoise(0.1f, 8);
  const double before = interiorVariance(im.lu, im.w, im.h, 20);
  for (FilterKernel k : kKernels) {
    PixelFilterSettings s = settingsFor(k);
    s.sigmaS = 3.0f;
    const FilteredBuffer fb = filterHighVariance(im.input(), s);
    const double after = interiorVariance(fb.radiance, im.w, im.h, 20);
    const double r = interiorMean(fb.reduction, im.w, im.h, 20);
    // Brute force: r is exact up to the sampling error of the measured variance.
    const double tol = k == FilterKernel::Bilateral ? 0.15 : 0.3;
    EXPECT_NEAR(after / before / r, 1.0, tol) << name(k) << " r=" << r;
    std::printf("%s: measured variance ratio %.5f, mean r %.5f\n", name(k), after / before, r);
  }
}

TEST(PixelFilter, FastKernelsAreCloseToBruteForceOnASmoothNoisyImage) {
  Images im(128, 128);
  im.each([&](std::uint32_t x, std::uint32_t y, std::size_t i) {
    im.lu[i] = vec3(1.0f + 0.5f * std::sin(float(x) / 20.0f) * std::cos(float(y) / 25.0f));
    im.colour[i] = vec3(0.5f + 0.002f * float(x) / 128.0f);  // a smooth range gradient
  });
  im.addNoise(0.1f, 9);
  const FilteredBuffer ref = filterHighVariance(im.input(), settingsFor(FilterKernel::Bilateral));
  for (FilterKernel k : {FilterKernel::Separable, FilterKernel::Atrous}) {
    const FilteredBuffer fb = filterHighVariance(im.input(), settingsFor(k));
    double e = 0, n = 0;
    for (std::uint32_t y = 24; y < im.h - 24; ++y)
      for (std::uint32_t x = 24; x < im.w - 24; ++x) {
        const double d = fb.radiance[im.at(x, y)].x - ref.radiance[im.at(x, y)].x;
        e += d * d;
        n += 1;
      }
    // Input noise is 0.1; both outputs keep about 0.1 sqrt(r) ~ 0.004 of it.
    EXPECT_LT(std::sqrt(e / n), 0.01) << name(k);
    std::printf("%s vs brute force: rms difference %.4f\n", name(k), std::sqrt(e / n));
  }
}

TEST(PixelFilter, ThreadCountDoesNotChangeABit) {
  Images im(70, 50);
  std::mt19937 rng(10);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  im.each([&](std::uint32_t x, std::uint32_t, std::size_t i) {
    im.colour[i] = vec3(x < 30 ? 0.2f : 0.6f, 0.3f + 0.02f * u(rng), 0.4f);
    im.depth[i] = u(rng) < 0.05f ? kInf : 2.0f;
  });
  im.addNoise(0.2f, 11);
  for (FilterKernel k : kKernels)
    for (bool extras : {false, true}) {
      PixelFilterSettings s = settingsFor(k);
      s.adaptiveWidth = s.antialiasRecovery = s.spikeRemoval = extras;
      std::vector<FilteredBuffer> fbs;
      std::vector<BlendResult> bs;
      for (int t : {1, 2, 3, 0}) {
        s.threads = t;
        fbs.push_back(filterHighVariance(im.input(), s));
        bs.push_back(blend(im.input(), fbs.back(), s));
      }
      for (std::size_t i = 1; i < fbs.size(); ++i) {
        EXPECT_EQ(fbs[i].radiance, fbs[0].radiance) << name(k);
        EXPECT_EQ(fbs[i].variance, fbs[0].variance) << name(k);
        EXPECT_EQ(fbs[i].reduction, fbs[0].reduction) << name(k);
        EXPECT_EQ(bs[i].radiance, bs[0].radiance) << name(k);
      }
    }
}

TEST(PixelFilter, AdaptiveWidthFollowsVarianceWithinTheGuideInterval) {
  Images im(16, 16);
  im.samples = 16;  // guide = sigmaS / 4 = 2: sigma in [2, 8]
  PixelFilterSettings s = settingsFor(FilterKernel::Bilateral);
  s.adaptiveWidth = true;
  im.var.assign(im.var.size(), vec3(1e-9f));
  for (float sg : filterHighVariance(im.input(), s).sigma) EXPECT_FLOAT_EQ(sg, 2.0f) << "never below the guide";
  im.var.assign(im.var.size(), vec3(100.0f));
  for (float sg : filterHighVariance(im.input(), s).sigma) EXPECT_FLOAT_EQ(sg, 8.0f);
  // No variance at all is no evidence of convergence: the widest kernel.
  im.var.assign(im.var.size(), vec3(0.0f));
  for (float sg : filterHighVariance(im.input(), s).sigma) EXPECT_FLOAT_EQ(sg, 8.0f);
  // In between: u = 0.05 / 0.25 = 0.2, target f = 0.005, e = 0.5 sqrt(40) - 0.5.
  im.var.assign(im.var.size(), vec3(0.05f));
  const float want = 1.5f * (0.5f * std::sqrt(40.0f) - 0.5f);
  EXPECT_NEAR(filterHighVariance(im.input(), s).sigma[im.at(8, 8)], want, 1e-3f);
}

TEST(PixelFilter, MixedPixelsTakeTheirSidesByCoverage) {
  // A silhouette column (x = 24) covering a quarter of the right-hand
  // surface: its range colour lies a quarter of the way from the left's to
  // the right's and its flash samples disagree. Its own few samples were
  // all black, as at 8 spp in a dim room; the left shows 1, the right 3.
  Images im(48, 32);
  const std::uint32_t edge = 24;
  im.spread.assign(im.lu.size(), 0.0f);
  im.each([&](std::uint32_t x, std::uint32_t, std::size_t i) {
    im.colour[i] = vec3(x < edge ? 0.2f : x > edge ? 0.8f : 0.35f);
    im.lu[i] = vec3(x < edge ? 1.0f : x > edge ? 3.0f : 0.0f);
    if (x == edge) im.spread[i] = 0.3f;
  });
  for (FilterKernel k : kKernels) {
    const FilteredBuffer fb = filterHighVariance(im.input(), settingsFor(k));
    EXPECT_NEAR(fb.radiance[im.at(edge, 16)].x, 0.75f * 1.0f + 0.25f * 3.0f, 0.05f) << name(k);
    EXPECT_NEAR(fb.radiance[im.at(edge - 3, 16)].x, 1.0f, 1e-4f) << name(k) << ": the sides stay as they were";
    EXPECT_NEAR(fb.radiance[im.at(edge + 3, 16)].x, 3.0f, 1e-4f) << name(k);
  }
  // Without the spread, the column gathers only itself: black.
  im.spread.clear();
  EXPECT_LT(filterHighVariance(im.input(), settingsFor(FilterKernel::Bilateral)).radiance[im.at(edge, 16)].x, 0.05f);
}

TEST(PixelFilter, AntialiasRecoveryFiltersPixelsOnAnAntialiasedEdge) {
  // Range A left, B right; the column between them is an antialiased edge
  // with a different coverage on every row, so its range colours match
  // nothing but themselves.
  Images im(64, 64);
  const vec3 A(0.2f), B(0.8f);
  const std::uint32_t edge = 32;
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> cover(0.2f, 0.8f);
  std::vector<float> alpha(im.h);
  for (auto& a : alpha) a = cover(rng);
  std::vector<float> truth(im.w * im.h);
  im.each([&](std::uint32_t x, std::uint32_t y, std::size_t i) {
    const float a = x < edge ? 1.0f : x > edge ? 0.0f : alpha[y];
    im.colour[i] = a * A + (1 - a) * B;
    truth[i] = a * 1.0f + (1 - a) * 3.0f;
    im.lu[i] = vec3(truth[i]);
  });
  im.addNoise(0.3f, 13);
  auto edgeError = [&](bool aa, double* meanR) {
    PixelFilterSettings s = settingsFor(FilterKernel::Separable);
    s.antialiasRecovery = aa;
    const FilteredBuffer fb = filterHighVariance(im.input(), s);
    double e = 0, r = 0;
    for (std::uint32_t y = 2; y < im.h - 2; ++y) {
      const double d = fb.radiance[im.at(edge, y)].x - truth[im.at(edge, y)];
      e += d * d;
      r += fb.reduction[im.at(edge, y)];
    }
    *meanR = r / (im.h - 4);
    return std::sqrt(e / (im.h - 4));
  };
  double rPlain = 0, rAa = 0;
  const double plain = edgeError(false, &rPlain);
  const double recovered = edgeError(true, &rAa);
  // Without the edge model an edge pixel gathers only the few rows whose
  // coverage happens to be close to its own: about half the input noise
  // (0.3) stays. With it, each edge pixel mixes its two sides' averages.
  EXPECT_GT(plain, 0.1);
  EXPECT_GT(rPlain, 0.15);
  EXPECT_LT(recovered, 0.4 * plain) << "plain " << plain;
  EXPECT_LT(rAa, 0.4 * rPlain) << "plain " << rPlain;
  std::printf("edge rms: plain %.3f recovered %.3f; r: plain %.3f recovered %.3f\n", plain, recovered, rPlain, rAa);
}

// A flat wall lit by rare bright paths (a sparse field of spikes, as at 8
// spp in a room lit only indirectly): the a-trous filter must not print
// the lattice of its level steps. A periodic pattern of period P puts a
// peak in the autocorrelation at lag P (a peak in the power spectrum at
// frequency 1/P); the filtered image's autocorrelation at each level's
// step must fall smoothly with the lag instead.
TEST(PixelFilter, AtrousPrintsNoGridOfItsSteps) {
  Images im(160, 160);
  std::mt19937 rng(21);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  im.each([&](std::uint32_t, std::uint32_t, std::size_t i) {
    im.lu[i] = vec3(u(rng) < 0.02f ? 50.0f : 0.0f);
    im.var[i] = vec3(12.0f);
  });
  PixelFilterSettings s = settingsFor(FilterKernel::Atrous);
  const FilteredBuffer fb = filterHighVariance(im.input(), s);
  double mean = 0;
  for (const auto& l : fb.radiance) mean += l.x;
  mean /= double(fb.radiance.size());
  // Autocorrelation along x and y, averaged, away from the borders.
  auto correlation = [&](int lag) {
    double sum = 0, norm = 0;
    for (int y = 24; y < 136; ++y)
      for (int x = 24; x < 136; ++x) {
        const double a = fb.radiance[im.at(x, y)].x - mean;
        sum += a * (fb.radiance[im.at(x + lag, y)].x - mean) + a * (fb.radiance[im.at(x, y + lag)].x - mean);
        norm += 2 * a * a;
      }
    return sum / norm;
  };
  // Level steps of sigmaS 8 over 3 levels: 8 sqrt(3/63) 2^(k-1) = 1.75, 3.5, 7.
  for (int lag : {2, 4, 7, 14}) {
    const double before = correlation(lag - 1), at = correlation(lag), after = correlation(lag + 1);
    EXPECT_LT(at, std::max(before, after) + 0.02)
        << "autocorrelation peaks at lag " << lag << ": " << before << ", " << at << ", " << after;
  }
}

}  // namespace
