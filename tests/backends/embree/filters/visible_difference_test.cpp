// The simplified visible-difference predictor and the photon-count
// stopping rule built on it.
#include "test_scenes.hpp"

#include "tsr/embree/error.hpp"
#include "tsr/embree/photon_budget.hpp"
#include "tsr/embree/rng.hpp"
#include "tsr/embree/visible_difference.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace tsr::embree {
namespace {

constexpr std::uint32_t kSize = 64;

std::vector<float> flat(float v) { return std::vector<float>(kSize * kSize, v); }

// 4 x 4 pixel blocks of 0.25 or 0.75: a busy, high-contrast background.
std::vector<float> busy() {
  std::vector<float> img(kSize * kSize);
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      Rng rng(Rng::pixelKey(7, x / 4, y / 4), 0);
      img[y * kSize + x] = rng.uniform() < 0.5f ? 0.25f : 0.75f;
    }
  return img;
}

// img plus zero-mean white noise of amplitude a (relative to 0.5).
std::vector<float> noisy(std::vector<float> img, float a) {
  for (std::uint32_t i = 0; i < img.size(); ++i)
    img[i] += 0.5f * a * (2.0f * Rng(Rng::pixelKey(3, i, 0), 0).uniform() - 1.0f);
  return img;
}

TEST(EmbreeVisibleDifference, IdenticalImagesDoNotDiffer) {
  const auto img = busy();
  const VisibleDifference d = predictVisibleDifference(img, img, kSize, kSize);
  EXPECT_EQ(d.fractionVisible, 0.0f);
  EXPECT_EQ(d.meanJnd, 0.0f);
}

TEST(EmbreeVisibleDifference, StrongerNoiseIsMoreVisible) {
  const auto base = flat(0.5f);
  float previous = 0.0f;
  for (float a : {0.002f, 0.01f, 0.04f, 0.16f}) {
    const VisibleDifference d = predictVisibleDifference(base, noisy(base, a), kSize, kSize);
    EXPECT_GT(d.meanJnd, previous) << "amplitude " << a;
    previous = d.meanJnd;
  }
  EXPECT_LT(predictVisibleDifference(base, noisy(base, 0.002f), kSize, kSize).fractionVisible, 0.05f);
  EXPECT_GT(predictVisibleDifference(base, noisy(base, 0.16f), kSize, kSize).fractionVisible, 0.5f);
}

TEST(EmbreeVisibleDifference, ABusyBackgroundMasksNoise) {
  const auto plain = flat(0.5f), textured = busy();
  const float onPlain = predictVisibleDifference(plain, noisy(plain, 0.04f), kSize, kSize).meanJnd;
  const float onBusy = predictVisibleDifference(textured, noisy(textured, 0.04f), kSize, kSize).meanJnd;
  EXPECT_LT(onBusy, 0.7f * onPlain) << "plain " << onPlain << ", busy " << onBusy;
}

TEST(EmbreeVisibleDifference, RejectsMismatchedImages) {
  EXPECT_THROW(predictVisibleDifference(flat(1.0f), std::vector<float>(3), kSize, kSize), Error);
  VisibleDifferenceSettings bad;
  bad.pixelsPerDegree = 0.0f;
  EXPECT_THROW(predictVisibleDifference(flat(1.0f), flat(1.0f), kSize, kSize, bad), Error);
}

TEST(EmbreePhotonBudget, DoublesPhotonsUntilTheNoiseIsInvisible) {
  Scene scene(test::sharedDevice());
  const Camera camera = test::cornellBox(scene, 0);
  const Region region{32, 32, 0, 0, 32, 32};
  RenderSettings rs;
  rs.samplesPerPass = 4;
  Renderer renderer(rs);
  PhotonSettings ps;
  ps.elementSize = 70.0f;
  ps.tMax = 5;
  ps.photonsPerFrame = 1000;
  auto choose = [&](float threshold) {
    PhotonBudgetSettings b;
    b.threshold = threshold;
    b.maxRounds = 8;
    return choosePhotonsPerFrame(
        scene, renderer, camera, region, [](Scene&, std::int64_t) {}, 2, 5, ps, b);
  };
  const PhotonBudget loose = choose(0.3f), strict = choose(0.05f);
  EXPECT_GT(strict.photonsPerFrame, ps.photonsPerFrame);
  EXPECT_GE(strict.photonsPerFrame, loose.photonsPerFrame);
  EXPECT_LE(loose.fractionVisible, 0.3f);
  EXPECT_LE(strict.fractionVisible, 0.05f);
  EXPECT_EQ(strict.photonsPerFrame, ps.photonsPerFrame << (strict.rounds - 1));
}

}  // namespace
}  // namespace tsr::embree
