// The change log lets a consumer that paused catch up, or tells it to resync.
#include <gtest/gtest.h>

#include "random_edits.hpp"
#include "tsr/sg/changes/change_log.hpp"
#include "tsr/sg/scene.hpp"

using namespace tsr::sg;

TEST(ChangeLog, CatchUpFromAnyVersionStillHeld) {
  Scene source;
  ChangeLog log(8);
  test::RandomEditor edit(source, 3);
  Scene paused;  // stops following at version 4
  for (int frame = 1; frame <= 12; ++frame) {
    for (int i = 0; i < 5; ++i) edit.editOne();
    auto list = source.commit();
    log.append(list);
    if (frame <= 4) paused.apply(*list);
  }
  EXPECT_EQ(log.size(), 8u);
  EXPECT_EQ(log.newestVersion(), 12u);
  EXPECT_EQ(log.oldestBaseVersion(), 4u);

  auto result = log.since(paused.version());
  ASSERT_EQ(result.status, ChangeLog::CatchUp::Deltas);
  ASSERT_EQ(result.lists.size(), 8u);
  for (const auto& list : result.lists) paused.apply(*list);
  EXPECT_EQ(paused.contentHash(), source.contentHash());
  EXPECT_EQ(log.since(12).status, ChangeLog::CatchUp::UpToDate);
}

TEST(ChangeLog, TooFarBehindMeansStartAgainFromASnapshot) {
  Scene source;
  ChangeLog log(4);
  Scene behind;
  source.create<Group>();
  behind.apply(*source.commit());  // version 1, never logged
  for (int frame = 0; frame < 10; ++frame) {
    source.create<Transform>();
    log.append(source.commit());
  }
  EXPECT_EQ(log.since(behind.version()).status, ChangeLog::CatchUp::TooFarBehind);
  EXPECT_EQ(log.since(99).status, ChangeLog::CatchUp::TooFarBehind) << "from the future";
  Scene fresh;
  fresh.apply(*source.snapshot());
  EXPECT_EQ(fresh.contentHash(), source.contentHash());
}

TEST(ChangeLog, RefusesListsOutOfOrder) {
  Scene source;
  ChangeLog log(4);
  auto v1 = source.commit();
  auto v2 = source.commit();
  auto v3 = source.commit();
  log.append(v1);
  EXPECT_THROW(log.append(v3), std::invalid_argument);
  log.append(v2);
  EXPECT_THROW(log.append(source.snapshot()), std::invalid_argument);
  EXPECT_THROW(ChangeLog(0), std::invalid_argument);
}
