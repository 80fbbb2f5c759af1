// rank() against a brute-force count over the same id buffer.
#include <gtest/gtest.h>

#include <map>

#include "test_scenes.hpp"
#include "tsr/cov/ranking.hpp"

using namespace tsr::cov;

namespace {
std::vector<Coverage> bruteForce(const IdBuffer& ids) {
  std::map<ObjectId, std::uint64_t> count;
  for (std::uint32_t y = 0; y < ids.height(); ++y)
    for (std::uint32_t x = 0; x < ids.width(); ++x)
      if (ObjectId id = ids.id(x, y); id != kBackground) ++count[id];
  std::vector<Coverage> out;
  for (const auto& [id, n] : count) out.push_back({id, n, double(n) / double(ids.ids.size())});
  std::stable_sort(out.begin(), out.end(), [](const Coverage& a, const Coverage& b) { return a.pixels > b.pixels; });
  return out;
}
}  // namespace

TEST(Ranking, EqualsBruteForceCountOfTheIdBuffer) {
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    EmbreeIdRenderer r;
    test::load(r, test::randomScene(seed, 300, 40));
    IdBuffer ids = r.render(test::straightCamera(), Region::full(211, 157));
    auto ranking = rank(ids);
    auto expected = bruteForce(ids);
    EXPECT_GT(expected.size(), 10u) << "the scene shows many objects";
    EXPECT_EQ(ranking, expected) << "seed " << seed;
    std::uint64_t sum = backgroundPixels(ids.ids);
    for (const auto& c : ranking) sum += c.pixels;
    EXPECT_EQ(sum, 211u * 157u);
  }
}

TEST(Ranking, TiesGoByIdAndBackgroundIsLeftOut) {
  std::vector<ObjectId> ids = {5, 5, 0, 3, 3, 0, 0, 9, 2, 2, 2};
  auto ranking = rank(ids);
  ASSERT_EQ(ranking.size(), 4u);
  EXPECT_EQ(ranking[0], (Coverage{2, 3, 3.0 / 11}));
  EXPECT_EQ(ranking[1], (Coverage{3, 2, 2.0 / 11}));
  EXPECT_EQ(ranking[2], (Coverage{5, 2, 2.0 / 11}));
  EXPECT_EQ(ranking[3], (Coverage{9, 1, 1.0 / 11}));
  EXPECT_EQ(backgroundPixels(ids), 3u);
  EXPECT_TRUE(rank(std::vector<ObjectId>(1000, kBackground)).empty());
}

TEST(Ranking, LargeBufferCountedInParallelIsExact) {
  // More than one chunk per thread, with runs crossing chunk borders.
  std::vector<ObjectId> ids(1 << 20);
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<ObjectId>((i / 1000) % 37);
  std::map<ObjectId, std::uint64_t> count;
  for (ObjectId id : ids) ++count[id];
  auto ranking = rank(ids);
  ASSERT_EQ(ranking.size(), 36u);
  for (const auto& c : ranking) EXPECT_EQ(c.pixels, count[c.id]) << c.id;
}

TEST(Ranking, ThreadCountAndTileSizeDoNotChangeTheIds) {
  auto scene = test::randomScene(11, 200, 50);
  EmbreeIdRenderer one({1, 4});
  EmbreeIdRenderer many({0, 64});
  test::load(one, scene);
  test::load(many, scene);
  const Region region = Region::full(123, 77);
  EXPECT_EQ(one.render(test::straightCamera(), region).ids, many.render(test::straightCamera(), region).ids);
}
