#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>

#include "tsr/backend/irradiance_volume.hpp"

using namespace tsr::backend;

TEST(IrradianceVolume, EqualAreaMappingRoundTrips) {
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j) {
      const glm::vec2 p((float(i) + 0.5f) / 64.0f, (float(j) + 0.5f) / 64.0f);
      const glm::vec3 d = equalAreaSquareToSphere(p);
      ASSERT_NEAR(glm::length(d), 1.0f, 1e-5f);
      const glm::vec2 back = equalAreaSphereToSquare(d);
      EXPECT_NEAR(back.x, p.x, 1e-4f) << i << "," << j;
      EXPECT_NEAR(back.y, p.y, 1e-4f) << i << "," << j;
    }
}

TEST(IrradianceVolume, EqualAreaTexelsSeeEqualShares) {
  // Uniform points of the square are uniform directions: each octant holds
  // an eighth of a fine grid of them.
  int octants[8] = {};
  constexpr int n = 256;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const glm::vec3 d = equalAreaSquareToSphere({(float(i) + 0.5f) / n, (float(j) + 0.5f) / n});
      ++octants[(d.x > 0) + 2 * (d.y > 0) + 4 * (d.z > 0)];
    }
  for (int o : octants) EXPECT_NEAR(double(o) / (n * n), 0.125, 0.002);
}

TEST(IrradianceVolume, ConstantRadianceGivesPiTimesItOnEveryNormal) {
  // Each face gathers pi L from a constant L, and a normal's squared
  // components add up to one: E(n) = pi L whatever n faces.
  IrradianceVolume v = IrradianceVolume::over({0, 0, 0}, {1, 1, 1}, 8);
  ASSERT_EQ(v.probeCount(), 8u);
  const float radiance = 0.5f;
  constexpr int n = 128;
  std::array<float, IrradianceVolume::kFaces> sums{};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const auto c = faceCosines(equalAreaSquareToSphere({(float(i) + 0.5f) / n, (float(j) + 0.5f) / n}));
      for (std::uint32_t f = 0; f < IrradianceVolume::kFaces; ++f) sums[f] += radiance * c[f];
    }
  for (std::uint32_t f = 0; f < IrradianceVolume::kFaces; ++f)
    v.irradiance[f] = glm::vec4(glm::vec3(sums[f] * 4.0f * 3.14159265f / (n * n)), f == 0);
  for (const glm::vec3 normal : {glm::vec3(0, 0, 1), glm::vec3(0, -1, 0), glm::normalize(glm::vec3(1, 2, -3))})
    EXPECT_NEAR(v.irradianceAt(0, normal).x, 3.14159265f * radiance, 2e-3f);
}

TEST(IrradianceVolume, LightFromOneSideIsReadInFullFacingIt) {
  // A lit floor below a ceiling: what faces it gets all of it, what faces
  // away nothing (order-1 harmonics read 3/4 and 1/4).
  IrradianceVolume v = IrradianceVolume::over({0, 0, 0}, {1, 1, 1}, 8);
  v.irradiance[3] = glm::vec4(2.0f);  // -y: light arriving from below
  EXPECT_FLOAT_EQ(v.irradianceAt(0, {0, -1, 0}).x, 2.0f);
  EXPECT_FLOAT_EQ(v.irradianceAt(0, {0, 1, 0}).x, 0.0f);
  EXPECT_FLOAT_EQ(v.irradianceAt(0, glm::normalize(glm::vec3(1, -1, 0))).x, 1.0f);
}

TEST(IrradianceVolume, GridKeepsWithinItsProbesAndOffFlatPlanes) {
  const IrradianceVolume room = IrradianceVolume::over({-1, 0, -1}, {1, 2, 1}, 512);
  EXPECT_LE(room.probeCount(), 512u);
  EXPECT_GE(room.probeCount(), 256u) << "a cube-like room uses most of its probes";
  // A flat quad: two probes across it, none in its plane.
  const IrradianceVolume flat = IrradianceVolume::over({-1, 0, -1}, {1, 0, 1}, 512);
  EXPECT_EQ(flat.counts.y, 2u);
  for (std::size_t p = 0; p < flat.probeCount(); ++p) EXPECT_NE(flat.probePosition(p).y, 0.0f);
  EXPECT_LE(flat.probeCount(), 512u);
  // Probes stand at cell centres inside the grown box.
  const glm::vec3 first = room.probePosition(0);
  EXPECT_GT(first.x, room.min.x);
  EXPECT_LT(first.x, room.min.x + room.cellSize().x);
}
