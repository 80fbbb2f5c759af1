// Properties of the Embree viewport's pixel filtering, measured through a
// real viewport on a small image against a reference rendered in the test
// (relMSE as in the quality harness): filtering lowers the error at low
// spp, fades out as the image converges, and its threshold is a display
// setting that never throws samples away.
#include <gtest/gtest.h>

#include "../../bench/quality/rel_mse.hpp"
#include "../viewport_rig.hpp"
#include "tsr/med/embree/register.hpp"

using namespace tsr;

namespace {
constexpr std::uint32_t kSize = 48;

class PixelFilterQuality : public ::testing::Test {
 protected:
  PixelFilterQuality() : rig("embree", med::registerEmbree, "builtin:cornell", kSize) {
    rig.parameters.set("seed", std::int64_t{1});
    rig.parameters.set("maxDepth", std::int64_t{4});
    replica.apply(rig.source.commit());
  }
  std::unique_ptr<med::Viewport> viewport(std::int64_t spp, const std::string& filter) {
    auto vp = rig.registry.create(rig.settings(), contexts);
    vp->setParameter("spp", spp);
    vp->setParameter("filter", filter);
    return vp;
  }
  med::RenderStats render(med::Viewport& vp, med::FrameBuffer& out) {
    med::RenderControl control;
    control.outputs = std::vector<std::string>{"blend"};
    return vp.render(replica, rig.view(replica.scene()), out, control);
  }
  // Independent of the measured renders: another seed.
  const med::FrameBuffer& reference() {
    if (reference_.colour.empty()) {
      auto vp = viewport(256, "none");
      vp->setParameter("seed", std::int64_t{4242});
      render(*vp, reference_);
    }
    return reference_;
  }

  test::ViewportRig rig;
  sg::Replica replica;
  med::ContextPool contexts;
  med::FrameBuffer reference_;
};

}  // namespace

TEST_F(PixelFilterQuality, LowersRelMseAtEightSpp) {
  med::FrameBuffer unfiltered, filtered;
  auto plain = viewport(8, "none");
  render(*plain, unfiltered);
  auto pixel = viewport(8, "pixel");
  render(*pixel, filtered);
  const double eu = quality::relMse(unfiltered.colour, reference().colour);
  const double ef = quality::relMse(filtered.colour, reference().colour);
  EXPECT_LT(ef, 0.8 * eu) << "relMSE filtered " << ef << ", unfiltered " << eu;
}

TEST_F(PixelFilterQuality, BlendFactorRisesTowardsOneAsSamplesGrow) {
  // Consistency (s -> 1): the same viewport converging, its blend factor
  // read at growing sample counts. s is 1 once a pixel's relative variance
  // of the mean falls under the threshold; at the default 0.002 that takes
  // thousands of samples in this box (mean s about 0.2 at 512 spp, 0.45 at
  // 2048, 0.77 at 8192), so the test uses a coarser threshold to see the
  // limit within a few hundred samples.
  auto vp = viewport(8, "pixel");
  vp->setParameter("threshold", 0.05);
  std::vector<double> s;
  for (std::int64_t spp : {8, 64, 512}) {
    vp->setParameter("spp", spp);
    med::FrameBuffer image;
    ASSERT_EQ(render(*vp, image).samples, std::uint32_t(spp));
    ASSERT_EQ(image.outputs.count("blend"), 1u);
    s.push_back(quality::meanRed(image.outputs["blend"]));
  }
  EXPECT_LT(s[0], s[1]);
  EXPECT_LT(s[1], s[2]);
  EXPECT_GT(s[2], 0.8) << "mean s at 8, 64, 512 spp: " << s[0] << ", " << s[1] << ", " << s[2];
}

TEST_F(PixelFilterQuality, ChangingThresholdKeepsTheSamples) {
  auto vp = viewport(8, "pixel");
  vp->setParameter("threshold", 0.002);
  med::FrameBuffer first, second, third;
  ASSERT_EQ(render(*vp, first).samples, 8u);

  vp->setParameter("threshold", 0.05);
  const auto stats = render(*vp, second);
  EXPECT_EQ(stats.samples, 8u) << "a new threshold re-blends the samples it has";
  EXPECT_EQ(stats.rays, 0u) << "and traces nothing anew";
  EXPECT_GT(test::differingPixels(first, second), 0u) << "the image shows the new threshold";
  EXPECT_GT(quality::meanRed(second.outputs["blend"]), quality::meanRed(first.outputs["blend"]))
      << "a larger threshold keeps more of the unfiltered image";

  vp->setParameter("spp", std::int64_t{16});
  vp->setParameter("threshold", 0.01);
  EXPECT_EQ(render(*vp, third).samples, 16u) << "accumulation continues from 8";
  EXPECT_GT(test::differingPixels(second, third), 0u);
}
