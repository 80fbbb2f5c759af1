#include "tsr/embree/sampling.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tsr::embree {
namespace {

TEST(Sampling, CosSin2PiMatchesTheLibraryOverTheUnitInterval) {
  float worst = 0.0f;
  for (int i = 0; i <= 1 << 20; ++i) {
    const float u = float(i) / float(1 << 20);
    const glm::vec2 cs = cosSin2Pi(u);
    const double phi = 2.0 * std::numbers::pi * double(u);
    worst = std::max(worst, float(std::abs(cs.x - std::cos(phi))));
    worst = std::max(worst, float(std::abs(cs.y - std::sin(phi))));
  }
  EXPECT_LT(worst, 4e-7f);
}

TEST(Sampling, CosSin2PiIsExactAtTheQuadrants) {
  EXPECT_EQ(cosSin2Pi(0.0f), glm::vec2(1.0f, 0.0f));
  EXPECT_EQ(cosSin2Pi(0.25f), glm::vec2(-0.0f, 1.0f));
  EXPECT_EQ(cosSin2Pi(0.5f), glm::vec2(-1.0f, -0.0f));
  EXPECT_EQ(cosSin2Pi(0.75f), glm::vec2(0.0f, -1.0f));
}

TEST(Sampling, CosineHemisphereDirectionsAreUnitAndAbove) {
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j) {
      const glm::vec3 w = sampleCosineHemisphere({(i + 0.5f) / 64, (j + 0.5f) / 64});
      EXPECT_NEAR(glm::length(w), 1.0f, 1e-6f);
      EXPECT_GT(w.z, 0.0f);
    }
}

}  // namespace
}  // namespace tsr::embree
