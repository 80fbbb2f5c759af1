// The light tree (scene/light_tree.hpp): it picks each triangle as often
// as pmf() says (chi-squared), its probabilities sum to one, it never
// picks a lamp that faces away, it favours the lamps near a point; and a
// room of many lamps renders to the same image with the tree as with the
// choice by power (MIS consistent: a pmf off for BSDF-found lamps biases
// the image).
#include "scene/light_tree.hpp"
#include "scene/scene_state.hpp"
#include "test_scenes.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace tsr::embree::test {
namespace {

EmitterTriangle triangle(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) {
  EmitterTriangle t{p0, p1 - p0, p2 - p0, glm::vec3(0.0f), 0.0f};
  const glm::vec3 n = glm::cross(t.e1, t.e2);
  t.area = 0.5f * glm::length(n);
  t.normal = glm::normalize(n);
  return t;
}

// Small triangles scattered in a box, facing every way, of varied power.
struct Lamps {
  std::vector<EmitterTriangle> triangles;
  std::vector<float> power;
  explicit Lamps(int n, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < n; ++i) {
      const glm::vec3 c(8.0f * u(rng) - 4.0f, 4.0f * u(rng), 8.0f * u(rng) - 4.0f);
      const glm::vec3 a = 0.2f * (glm::vec3(u(rng), u(rng), u(rng)) - 0.5f);
      const glm::vec3 b = 0.2f * (glm::vec3(u(rng), u(rng), u(rng)) - 0.5f);
      triangles.push_back(triangle(c, c + a, c + b));
      power.push_back(triangles.back().area * (0.5f + 10.0f * u(rng)));
    }
  }
};

TEST(LightTree, PicksEachTriangleAsOftenAsItsPmf) {
  const Lamps lamps(120, 3);
  const LightTree tree(lamps.triangles, lamps.power);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const std::vector<std::pair<glm::vec3, glm::vec3>> points{
      {{0, 0, 0}, {0, 1, 0}}, {{3, 2, -3}, glm::normalize(glm::vec3(-1, 0, 1))}, {{0, 2, 0}, {0, 0, 0}}};
  for (const auto& [p, n] : points) {
    // Below 1 where traversal reaches a node whose children both face away
    // from p (its own bounds were looser): the lost draws pick nothing,
    // and the triangles there could not have lit p.
    double sum = 0.0;
    for (std::uint32_t i = 0; i < lamps.triangles.size(); ++i) sum += tree.pmf(p, n, i);
    EXPECT_LE(sum, 1.0 + 1e-4);
    EXPECT_GT(sum, 0.5);

    constexpr int kDraws = 200000;
    std::vector<int> count(lamps.triangles.size(), 0);
    int none = 0;
    for (int k = 0; k < kDraws; ++k) {
      std::uint32_t t = 0;
      float prob = 0.0f;
      if (!tree.sample(p, n, u(rng), t, prob)) {
        ++none;
        continue;
      }
      ASSERT_FLOAT_EQ(prob, tree.pmf(p, n, t));
      ++count[t];
    }
    double chi2 = 0.0;
    int bins = 0;
    if (sum < 1.0 - 1e-4) {
      const double expected = kDraws * (1.0 - sum);
      chi2 += (none - expected) * (none - expected) / expected;
      ++bins;
    } else {
      EXPECT_EQ(none, 0);
    }
    double restExpected = 0.0, restSeen = 0.0;
    for (std::uint32_t i = 0; i < count.size(); ++i) {
      const double expected = kDraws * tree.pmf(p, n, i);
      if (expected == 0.0) {
        EXPECT_EQ(count[i], 0) << "triangle " << i << " has pmf 0 but was picked";
        continue;
      }
      if (expected < 5.0) {
        restExpected += expected, restSeen += count[i];
        continue;
      }
      chi2 += (count[i] - expected) * (count[i] - expected) / expected;
      ++bins;
    }
    if (restExpected > 0.0) chi2 += (restSeen - restExpected) * (restSeen - restExpected) / restExpected, ++bins;
    // p ~ 1e-4 for up to 120 degrees of freedom.
    EXPECT_LT(chi2, bins + 5.0 * std::sqrt(2.0 * bins) + 10.0) << "bins " << bins;
  }
}

TEST(LightTree, NeverPicksALampThatFacesAwayAndFavoursNearOnes) {
  // Two lamps face down at height 1, one right above the point and one far
  // off; a third faces up, away from a point below it.
  std::vector<EmitterTriangle> t{triangle({-0.1f, 1, -0.1f}, {0.1f, 1, 0}, {-0.1f, 1, 0.1f}),
                                 triangle({19.9f, 1, -0.1f}, {20.1f, 1, 0}, {19.9f, 1, 0.1f}),
                                 triangle({-0.1f, 0.5f, -0.1f}, {-0.1f, 0.5f, 0.1f}, {0.1f, 0.5f, 0})};
  ASSERT_LT(t[0].normal.y, 0.0f);
  ASSERT_GT(t[2].normal.y, 0.0f);
  const std::vector<float> power{1.0f, 1.0f, 1.0f};
  const LightTree tree(t, power);
  const glm::vec3 p(0, 0, 0), n(0, 1, 0);
  EXPECT_EQ(tree.pmf(p, n, 2), 0.0f);
  EXPECT_GT(tree.pmf(p, n, 0), 0.99f);
  EXPECT_GT(tree.pmf(p, n, 1), 0.0f);  // far, but it does reach the point
}

// 36 small lamps over a floor, each lighting a patch: the image with the
// tree equals the image by power within their noise, at two depths.
glm::vec3 roomOfLamps(LightChoice choice, std::uint32_t depth, std::uint32_t spp, float* error) {
  Scene scene(sharedDevice());
  Material floor;
  floor.baseColor = glm::vec3(0.7f);
  floor.roughness = 0.6f;
  scene.addInstance(scene.addMesh(quad({-8, 0, 8}, {8, 0, 8}, {8, 0, -8}, {-8, 0, -8})), scene.addMaterial(floor),
                    glm::mat4(1.0f));
  Material lamp;
  lamp.baseColor = glm::vec3(0.0f);
  lamp.emission = glm::vec3(40.0f);
  const auto lampMaterial = scene.addMaterial(lamp);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      const float x = -5.0f + 2.0f * float(i), z = -5.0f + 2.0f * float(j), h = 0.1f;
      scene.addInstance(
          scene.addMesh(quad({x - h, 0.8f, z - h}, {x + h, 0.8f, z - h}, {x + h, 0.8f, z + h}, {x - h, 0.8f, z + h})),
          lampMaterial, glm::mat4(1.0f));
    }
  RenderSettings s;
  s.maxDepth = depth;
  s.samplesPerPass = spp;
  s.lightChoice = choice;
  s.seed = choice == LightChoice::Tree ? 1 : 2;
  Renderer renderer(s);
  constexpr std::uint32_t kSize = 32;
  FrameBuffer fb(kSize, kSize);
  const Camera cam = Camera::lookAt({0, 7, 7}, {0, 0, 0}, {0, 1, 0}, glm::radians(70.0f), 1.0f);
  render(renderer, scene, cam, Region::full(kSize, kSize), fb, 1);
  *error = meanStandardError(fb);
  return meanColour(fb);
}

TEST(LightTree, ManyLampsRenderAsWithTheChoiceByPower) {
  for (std::uint32_t depth : {1u, 3u}) {
    float treeError = 0.0f, powerError = 0.0f;
    const float tree = luminance(roomOfLamps(LightChoice::Tree, depth, 256, &treeError));
    const float power = luminance(roomOfLamps(LightChoice::Power, depth, 256, &powerError));
    EXPECT_LT(std::abs(tree - power), 4.0f * std::hypot(treeError, powerError) + 1e-5f)
        << "depth " << depth << ": tree " << tree << ", power " << power << " (+-" << treeError << ", " << powerError
        << ")";
    EXPECT_LT(treeError, powerError) << "depth " << depth << ": the tree should be the less noisy";
  }
}

}  // namespace
}  // namespace tsr::embree::test
