// Properties of the Embree viewport's pixel filtering, measured through a
// real viewport on a small image against a reference rendered in the test
// (relMSE as in the quality harness): filtering lowers the error at low
// spp, fades out as the image converges, and its threshold is a display
// setting that never throws samples away.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "../../bench/quality/rel_mse.hpp"
#include "../../bench/quality/seen_error.hpp"
#include "../viewport_rig.hpp"
#include "tsr/med/embree/register.hpp"

using namespace tsr;

namespace {
constexpr std::uint32_t kSize = 48;

// A scene followed by a replica, and fresh Embree viewports over it.
struct FilterRig {
  FilterRig(const std::string& scene, std::uint32_t size, std::int64_t maxDepth)
      : rig("embree", med::registerEmbree, scene, size) {
    rig.parameters.set("seed", std::int64_t{1});
    rig.parameters.set("maxDepth", maxDepth);
    replica.apply(rig.source.commit());
  }
  std::unique_ptr<med::Viewport> viewport(std::int64_t spp, const std::string& filter) {
    auto vp = rig.registry.create(rig.settings(), contexts);
    vp->setParameter("spp", spp);
    vp->setParameter("filter", filter);
    return vp;
  }
  // With the blend factor where the viewport has one.
  med::RenderStats render(med::Viewport& vp, med::FrameBuffer& out) {
    med::RenderControl control;
    if (vp.settings().parameters.all().at("filter") != med::ParameterValue(std::string("none")))
      control.outputs = std::vector<std::string>{"blend"};
    return vp.render(replica, rig.view(replica.scene()), out, control);
  }
  med::FrameBuffer render(med::Viewport& vp) {
    med::FrameBuffer out;
    render(vp, out);
    return out;
  }

  test::ViewportRig rig;
  sg::Replica replica;
  med::ContextPool contexts;
};

class PixelFilterQuality : public ::testing::Test, protected FilterRig {
 protected:
  PixelFilterQuality() : FilterRig("builtin:cornell", kSize, 4) {}
  // Independent of the measured renders: another seed.
  const med::FrameBuffer& reference() {
    if (reference_.colour.empty()) {
      auto vp = viewport(256, "none");
      vp->setParameter("seed", std::int64_t{4242});
      render(*vp, reference_);
    }
    return reference_;
  }

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

// Properties on scenes of the quality suite (tests/bench/quality/suite),
// which nobody tuned the filters on, by the seen error of the harness:
// what a person sees differ, once both images are displayed and de-grained.
namespace {

constexpr std::uint32_t kSuiteSize = 64;

class SuiteFilter : public ::testing::TestWithParam<const char*>, protected FilterRig {
 protected:
  SuiteFilter() : FilterRig(std::string(TSR_QUALITY_SUITE) + "/" + GetParam() + ".gltf", kSuiteSize, 6) {}
  quality::SeenError seen(const med::FrameBuffer& image, const med::FrameBuffer& against) {
    return quality::seenError(image.colour, against.colour, kSuiteSize, kSuiteSize);
  }
};

// At 8 spp the filtered worst tile beats the unfiltered one, on scenes of
// diffuse light, fine textures and thin geometry. Not on every scene:
// where the filter smears a focused caustic (caustics) or washes out a
// roughness-0.3 sphere's reflection (rough-metal) its worst tile is worse
// than the unfiltered one; docs/filtering.md lists those misses.
using SuitePreview = SuiteFilter;

TEST_P(SuitePreview, FilteredWorstTileBeatsUnfilteredAtEightSpp) {
  auto ref = viewport(2048, "none");
  ref->setParameter("seed", std::int64_t{777});
  const med::FrameBuffer reference = render(*ref);
  auto plainVp = viewport(8, "none");
  auto pixelVp = viewport(8, "pixel");
  const auto plain = seen(render(*plainVp), reference), filtered = seen(render(*pixelVp), reference);
  EXPECT_LT(filtered.worstTile, plain.worstTile)
      << GetParam() << ": worst tile at (" << filtered.worstX << ", " << filtered.worstY << ")";
  EXPECT_LT(filtered.whole, plain.whole) << GetParam();
  std::printf("%s, 8 spp, seen error whole / worst tile: unfiltered %.4f / %.4f, pixel %.4f / %.4f\n", GetParam(),
              plain.whole, plain.worstTile, filtered.whole, filtered.worstTile);
}

// Figure 4.19's claim on the suite's depth-of-field scene (a thin lens
// in the glTF, TSR_camera_lens): radiance filtering, which needs no sharp
// per-pixel edges, beats the unfiltered image at 8 spp in the worst tile.
// (On the motion-blurred scene it does not; docs/camera.md has the figures.)
TEST(SuiteDistributionEffects, RadianceFilterBeatsUnfilteredThroughALens) {
  FilterRig rig(std::string(TSR_QUALITY_SUITE) + "/defocus.gltf", kSuiteSize, 6);
  auto image = [&](std::int64_t spp, const char* filter, std::int64_t seed) {
    auto vp = rig.viewport(spp, filter);
    vp->setParameter("seed", seed);
    med::FrameBuffer out;
    vp->render(rig.replica, rig.rig.view(rig.replica.scene()), out);
    return out;
  };
  const med::FrameBuffer reference = image(2048, "none", 777);
  const auto plain = quality::seenError(image(8, "none", 1).colour, reference.colour, kSuiteSize, kSuiteSize);
  const auto filtered = quality::seenError(image(8, "radiance", 1).colour, reference.colour, kSuiteSize, kSuiteSize);
  EXPECT_LT(filtered.worstTile, plain.worstTile);
  std::printf("defocus, 8 spp, seen error whole / worst tile: unfiltered %.4f / %.4f, radiance %.4f / %.4f\n",
              plain.whole, plain.worstTile, filtered.whole, filtered.worstTile);
}

TEST_P(SuiteFilter, FilteredImageConvergesToTheUnfilteredOneTileByTile) {
  // One viewport's samples, shown unfiltered and filtered: the filter's
  // share fades as they grow, in every tile, so nothing it does survives.
  auto vp = viewport(64, "none");
  std::vector<double> gap;
  for (std::int64_t spp : {64, 1024}) {
    vp->setParameter("spp", spp);
    vp->setParameter("filter", std::string("none"));
    const med::FrameBuffer plain = render(*vp);
    vp->setParameter("filter", std::string("pixel"));
    gap.push_back(seen(render(*vp), plain).worstTile);
  }
  EXPECT_LT(gap[1], 0.5 * gap[0]) << GetParam() << ": worst tile gap at 64 spp " << gap[0] << ", at 1024 " << gap[1];
  EXPECT_LT(gap[1], 0.02) << GetParam();
  std::printf("%s: worst-tile gap filtered vs unfiltered: %.4f at 64 spp, %.4f at 1024\n", GetParam(), gap[0], gap[1]);
}

std::string sceneName(const ::testing::TestParamInfo<const char*>& info) {
  std::string name = info.param;
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

INSTANTIATE_TEST_SUITE_P(QualitySuite, SuiteFilter,
                         ::testing::Values("indirect-room", "rough-metal", "textures", "foggy-room", "fog-glass"),
                         sceneName);
INSTANTIATE_TEST_SUITE_P(QualitySuite, SuitePreview,
                         ::testing::Values("indirect-room", "textures", "grille", "foggy-room", "fog-glass"),
                         sceneName);

}  // namespace
