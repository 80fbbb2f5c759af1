// Array fields edited by sub-range: only the edited elements travel.
#include <gtest/gtest.h>

#include "tsr/sg/scene.hpp"
#include "tsr/sg/wire/wire_codec.hpp"

using namespace tsr::sg;

namespace {
std::vector<Vec3> ramp(std::size_t n) {
  std::vector<Vec3> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = Vec3(float(i), 0, 0);
  return v;
}

struct Fixture {
  Scene source, replica;
  Geometry* mesh = nullptr;
  Fixture() {
    mesh = &source.create<Geometry>();
    mesh->setPositions(ramp(10000));
    replica.apply(*source.commit());
  }
};
}  // namespace

TEST(ArrayRanges, OverlappingEditsMergeAndOnlyTheirElementsTravel) {
  Fixture f;
  std::vector<Vec3> five(5, Vec3(7));
  f.mesh->updatePositions(100, five);  // [100,105)
  f.mesh->updatePositions(103, five);  // [103,108) overlaps
  f.mesh->updatePositions(108, five);  // [108,113) touches
  f.mesh->updatePositions(9000, std::vector<Vec3>(2, Vec3(1)));
  auto list = f.source.commit();
  ASSERT_EQ(list->changes().size(), 1u);
  const RangedEdit* edit = list->changes()[0].rangedEdit(Geometry::Positions);
  ASSERT_NE(edit, nullptr);
  EXPECT_EQ(edit->length, 10000u);
  EXPECT_EQ(edit->ranges, (std::vector<ArrayRange>{{100, 113}, {9000, 9002}}));
  // 15 vectors of 12 bytes plus a little framing, not 120 kB.
  EXPECT_LT(encode(*list).size(), 15 * 12 + 64u);

  f.replica.apply(*list);
  EXPECT_EQ(f.replica.contentHash(), f.source.contentHash());
  EXPECT_EQ(f.replica.find<Geometry>(f.mesh->id())->positions()[110], Vec3(7));
}

TEST(ArrayRanges, WholeReplacementInTheSameFrameWins) {
  Fixture f;
  f.mesh->updatePositions(0, std::vector<Vec3>(1, Vec3(5)));
  f.mesh->setPositions(ramp(20));
  f.mesh->updatePositions(3, std::vector<Vec3>(1, Vec3(9)));
  auto list = f.source.commit();
  EXPECT_EQ(list->changes()[0].rangedEdit(Geometry::Positions), nullptr) << "goes whole";
  f.replica.apply(*list);
  EXPECT_EQ(f.replica.contentHash(), f.source.contentHash());
  EXPECT_EQ(f.replica.find<Geometry>(f.mesh->id())->positions().size(), 20u);
}

TEST(ArrayRanges, EditsOutsideTheArrayAreRefused) {
  Fixture f;
  EXPECT_THROW(f.mesh->updatePositions(9999, std::vector<Vec3>(2, Vec3(0))), SceneError);
  EXPECT_FALSE(f.source.hasPendingChanges());
}

TEST(ArrayRanges, ARangedEditForAnArrayOfAnotherLengthIsRejectedByTheReplica) {
  Fixture f;
  // The replica diverged: its array is shorter than the edit expects.
  Scene other;
  auto& g = other.create<Geometry>();
  g.setPositions(ramp(10));
  other.commit();
  // Give `other` the same version history length so only the length differs.
  f.mesh->updatePositions(2, std::vector<Vec3>(1, Vec3(3)));
  auto list = f.source.commit();
  std::uint64_t before = other.contentHash();
  EXPECT_THROW(other.apply(*list), ApplyError);
  EXPECT_EQ(other.contentHash(), before);
}
