#include "tsr/sg/array_range.hpp"

#include <gtest/gtest.h>

using tsr::sg::ArrayRange;
using tsr::sg::RangeSet;

TEST(RangeSet, MergesOverlappingAndTouchingRanges) {
  RangeSet s;
  s.add({10, 20});
  s.add({30, 40});
  s.add({0, 5});
  EXPECT_EQ(s.ranges(), (std::vector<ArrayRange>{{0, 5}, {10, 20}, {30, 40}}));
  s.add({18, 30});  // bridges two ranges, touching the second
  EXPECT_EQ(s.ranges(), (std::vector<ArrayRange>{{0, 5}, {10, 40}}));
  s.add({5, 10});
  EXPECT_EQ(s.ranges(), (std::vector<ArrayRange>{{0, 40}}));
  EXPECT_EQ(s.elementCount(), 40u);
}

TEST(RangeSet, IgnoresEmptyRangesAndKeepsContainedOnes) {
  RangeSet s;
  s.add({7, 7});
  EXPECT_TRUE(s.empty());
  s.add({0, 100});
  s.add({20, 30});
  EXPECT_EQ(s.ranges(), (std::vector<ArrayRange>{{0, 100}}));
}
