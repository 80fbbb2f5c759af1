// The short soak (issue 17): a few hundred builtin:animated frames on four
// real nodes in each cluster mode, with every fault injected once. The long
// run with a frame-rate bound is scripts/soak.sh.
#include <gtest/gtest.h>

#include "../../sanitizers/resident_scale.hpp"
#include "soak/soak_run.hpp"

namespace tsr::cluster::test {
namespace {

#if defined(__SANITIZE_ADDRESS__)
// ASan's quarantine holds up to 256 MiB of freed memory in each node.
constexpr long kRssSlackKiB = 512 * 1024;
#else
// Under TSan the nodes that stay up grow 87-90 MiB (shadow of what they touched).
constexpr long kRssSlackKiB = 64 * 1024 * tsr::test::kResidentScale;
#endif

class Soak : public ::testing::TestWithParam<ClusterMode> {};

TEST_P(Soak, ReplicasStayEqualAndEveryFaultRecovers) {
  SoakOptions o;
  o.mode = GetParam();
  o.frames = 300;
  o.hashEvery = 20;
  o.renderBinary = TSR_RENDER_BINARY;
  const SoakReport r = runSoak(o);
  std::cout << describe(r);
  EXPECT_GE(r.frames, o.frames);
  EXPECT_EQ(r.divergences, 0);
  EXPECT_EQ(r.failedFrames, 0);
  EXPECT_EQ(r.faults.size(), 6u);
  // Checks every hashEvery frames outside the faults and one after each.
  EXPECT_GE(r.hashChecks, static_cast<int>(r.faults.size()) + 3);
  EXPECT_EQ(r.nodesChecked, 4 * r.hashChecks) << "every node synchronised at every check";
  for (const auto& f : r.faults) {
    EXPECT_GE(f.recoverySeconds, 0.0) << f.name << " never recovered";
    EXPECT_EQ(f.detail.find("FAILED"), std::string::npos) << f.name << ": " << f.detail;
    EXPECT_EQ(f.detail.find("NOT"), std::string::npos) << f.name << ": " << f.detail;
  }
  ASSERT_EQ(r.start.size(), r.end.size());
  for (std::size_t i = 0; i < r.end.size(); ++i) {
    // Bounded, not a stopwatch: a few hundred frames may warm caches, but
    // neither memory nor descriptors may grow with the faults' connections.
    EXPECT_LT(r.end[i].rssKiB, r.start[i].rssKiB + kRssSlackKiB) << "node " << i;
    EXPECT_LE(r.end[i].fds, r.start[i].fds + 4) << "node " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Modes, Soak,
                         ::testing::Values(ClusterMode::Cooperative, ClusterMode::Tiled, ClusterMode::Stereo),
                         [](const auto& info) { return modeName(info.param); });

}  // namespace
}  // namespace tsr::cluster::test
