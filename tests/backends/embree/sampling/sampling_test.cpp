#include "tsr/embree/sampling.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tsr::embree {
namespace {

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
