// Several missed frames fold into one per-container view.
#include <gtest/gtest.h>

#include "random_edits.hpp"
#include "tsr/sg/changes/merged_changes.hpp"
#include "tsr/sg/replica.hpp"

using namespace tsr::sg;

TEST(MergedChanges, FoldsMasksRangesCreationsAndDestructions) {
  Scene s;
  auto& t = s.create<Transform>();
  auto& mesh = s.create<Geometry>();
  auto& doomed = s.create<Group>();
  mesh.setPositions(std::vector<Vec3>(100, Vec3(0)));
  auto base = s.commit();

  MergedChanges merged(base->version());
  t.setMatrix(Mat4(2.0f));
  mesh.updatePositions(10, std::vector<Vec3>(2, Vec3(1)));
  merged.add(*s.commit());
  t.setName("t");
  mesh.updatePositions(11, std::vector<Vec3>(4, Vec3(1)));
  auto& born = s.create<Light>();
  auto& ephemeral = s.create<Camera>();
  merged.add(*s.commit());
  born.setIntensity(5);
  const ContainerId ephemeralId = ephemeral.id(), doomedId = doomed.id();
  s.destroy(ephemeralId);
  s.destroy(doomedId);
  merged.add(*s.commit());

  const auto& e = merged.entries();
  EXPECT_EQ(e.at(t.id()).mask, fieldBit(Transform::Matrix) | fieldBit(Container::kName));
  const RangedEdit* r = e.at(mesh.id()).rangedEdit(Geometry::Positions);
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->ranges, (std::vector<ArrayRange>{{10, 15}}));
  EXPECT_TRUE(e.at(born.id()).created);
  EXPECT_FALSE(e.count(ephemeralId)) << "born and gone between two looks";
  EXPECT_TRUE(e.at(doomedId).destroyed);
  EXPECT_EQ(merged.version(), s.version());
}

TEST(MergedChanges, AWholeReplacementInAnyFrameWins) {
  Scene s;
  auto& mesh = s.create<Geometry>();
  mesh.setPositions(std::vector<Vec3>(10, Vec3(0)));
  MergedChanges merged(s.commit()->version());
  mesh.updatePositions(1, std::vector<Vec3>(1, Vec3(1)));
  merged.add(*s.commit());
  mesh.setPositions(std::vector<Vec3>(20, Vec3(0)));
  merged.add(*s.commit());
  mesh.updatePositions(2, std::vector<Vec3>(1, Vec3(1)));
  merged.add(*s.commit());
  EXPECT_EQ(merged.entries().at(mesh.id()).rangedEdit(Geometry::Positions), nullptr);
  EXPECT_TRUE(merged.entries().at(mesh.id()).changed(Geometry::Positions));
  EXPECT_THROW(merged.add(*s.snapshot()), std::invalid_argument);
}

TEST(Replica, LogsDeltasAndRestartsItsLogOnASnapshot) {
  Scene source;
  test::RandomEditor edit(source, 9);
  for (int i = 0; i < 30; ++i) edit.editOne();
  source.commit();
  Replica replica(4);
  replica.apply(source.snapshot());
  EXPECT_EQ(replica.log().since(0).status, ChangeLog::CatchUp::TooFarBehind)
      << "a consumer of the empty replica must reconvert";
  EXPECT_EQ(replica.log().since(replica.version()).status, ChangeLog::CatchUp::UpToDate);
  const std::uint64_t joined = replica.version();
  for (int f = 0; f < 3; ++f) {
    for (int i = 0; i < 5; ++i) edit.editOne();
    replica.apply(source.commit());
  }
  auto since = replica.log().since(joined);
  ASSERT_EQ(since.status, ChangeLog::CatchUp::Deltas);
  EXPECT_EQ(since.lists.size(), 3u);
  EXPECT_EQ(replica.scene().contentHash(), source.contentHash());
}
