// The rasterizer lit by the path tracer's bounced light (the "bouncedLight"
// parameter: an irradiance volume the Embree back-end traces, read instead
// of the constant ambient term), through the real viewports.
#include <gtest/gtest.h>

#include <spdlog/spdlog.h>

#include "../viewport_rig.hpp"
#include "test_scenes.hpp"
#include "tsr/med/embree/register.hpp"
#include "tsr/med/vulkan/register.hpp"
#include "vulkan_viewport.hpp"

using namespace tsr;

namespace {
constexpr std::uint32_t kSize = 64;

void registerBoth(med::ViewportRegistry& registry) {
  med::registerVulkan(registry);
  med::registerEmbree(registry);
}

struct CornellRig : test::ViewportRig {
  CornellRig() : ViewportRig("vulkan", registerBoth, "builtin:cornell", kSize) { source.commit(); }

  med::FrameBuffer render(const std::string& backend, med::Parameters parameters) {
    test::Follower f;
    f.replica.apply(source.snapshot());
    med::ViewportSettings s = settings();
    s.backend = backend;
    s.parameters = std::move(parameters);
    f.viewport = registry.create(s, f.contexts);
    f.viewport->render(f.replica, view(f.replica.scene()), f.image);
    return f.image;
  }
};

// Mean over 4x4 blocks: the path tracer's grain averages out, what the
// light does (a dark face, a coloured wall) stays.
std::vector<glm::vec3> blocks(const med::FrameBuffer& image) {
  std::vector<glm::vec3> out((kSize / 4) * (kSize / 4), glm::vec3(0.0f));
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x)
      out[(y / 4) * (kSize / 4) + x / 4] += glm::vec3(image.colour[image.index(x, y)]) / 16.0f;
  return out;
}

// relMSE of a's blocks against reference's: (a - r)^2 / (r^2 + 0.01).
double blockRelMse(const med::FrameBuffer& a, const med::FrameBuffer& reference) {
  const auto ab = blocks(a), rb = blocks(reference);
  double sum = 0;
  for (std::size_t i = 0; i < ab.size(); ++i)
    for (int c = 0; c < 3; ++c) sum += (ab[i][c] - rb[i][c]) * (ab[i][c] - rb[i][c]) / (rb[i][c] * rb[i][c] + 0.01);
  return sum / (3.0 * double(ab.size()));
}

med::Parameters withBouncedLight(const std::string& mode) {
  med::Parameters p;
  p.set("bouncedLight", mode);
  return p;
}
}  // namespace

TEST(BouncedLight, CornellBoxComesCloserToThePathTracer) {
  CornellRig rig;
  med::Parameters traced;
  traced.set("spp", std::int64_t{256});
  const med::FrameBuffer reference = rig.render("embree", traced);
  const med::FrameBuffer probes = rig.render("vulkan", withBouncedLight("probes"));
  const med::FrameBuffer ambient = rig.render("vulkan", withBouncedLight("ambient"));
  test::keepImage("bounced_light_reference", reference);
  test::keepImage("bounced_light_probes", probes);
  test::keepImage("bounced_light_ambient", ambient);
  const double withProbes = blockRelMse(probes, reference), withAmbient = blockRelMse(ambient, reference);
  spdlog::info("builtin:cornell, relMSE of 4x4 blocks against the path tracer: probes {:.4f}, ambient {:.4f}",
               withProbes, withAmbient);
  RecordProperty("probes", std::to_string(withProbes));
  RecordProperty("ambient", std::to_string(withAmbient));
  EXPECT_LT(withProbes, 0.5 * withAmbient);
  // "auto" takes the probes for a scene this small.
  EXPECT_EQ(test::differingPixels(rig.render("vulkan", withBouncedLight("auto")), probes), 0u);
}

TEST(BouncedLight, AnEditIsTracedAgainInTurnsAndConvergesToAFreshVolume) {
  CornellRig rig;
  med::Parameters p = withBouncedLight("probes");
  p.set("probesPerFrame", std::int64_t{200});
  rig.parameters = p;
  test::Follower follower;
  follower.replica.apply(rig.source.snapshot());
  follower.viewport = rig.registry.create(rig.settings(), follower.contexts);
  auto& viewport = dynamic_cast<med::vulkan_mediator::VulkanViewport&>(*follower.viewport);
  med::RenderControl interactive;  // the viewer's frames: probes traced again in turns
  interactive.interactive = true;
  const auto render = [&] {
    viewport.render(follower.replica, rig.view(follower.replica.scene()), follower.image, interactive);
  };
  render();
  EXPECT_EQ(viewport.staleProbes(), 0u) << "the first frame traces every probe";
  const med::FrameBuffer before = follower.image;

  // Move the mirror sphere sideways, within the room.
  const sg::ContainerId sphere = test::findNamed(rig.source, sg::ContainerType::Transform, "mirror sphere");
  ASSERT_NE(sphere, sg::kNoContainer);
  auto& t = *rig.source.find<sg::Transform>(sphere);
  sg::Mat4 m = t.matrix();
  m[3][0] -= 150.0f;
  t.setMatrix(m);
  follower.replica.apply(rig.source.commit());
  std::vector<std::size_t> stale;
  for (int frame = 0; frame < 3; ++frame) {
    render();
    stale.push_back(viewport.staleProbes());
  }
  const std::size_t probes = stale.front() + 200;
  ASSERT_GT(probes, 400u);
  ASSERT_LE(probes, 600u);
  EXPECT_EQ(stale, (std::vector<std::size_t>{probes - 200, probes - 400, 0}));
  EXPECT_GT(test::differingPixels(follower.image, before), 0u);
  // Once converged, the followed volume shows what a fresh one over the
  // moved scene shows (not bitwise: the moved block sits in the path
  // tracer's second level, so hits differ in their last bits).
  const med::FrameBuffer fresh = test::freshRender(rig);
  EXPECT_LT(blockRelMse(follower.image, fresh), 1e-4);

  // A frame that is not interactive (a file, a wall, an eye) waits for
  // every probe: one render after the next edit shows it all.
  m[3][0] += 150.0f;
  t.setMatrix(m);
  follower.replica.apply(rig.source.commit());
  follower.render(rig);
  EXPECT_EQ(viewport.staleProbes(), 0u);
  EXPECT_LT(blockRelMse(follower.image, before), 1e-4) << "the sphere is back where it was";
}

TEST(BouncedLight, ThePathTracersSceneIsConvertedOnceForItsViewportsAndTheRasterisersLight) {
  CornellRig rig;
  test::Follower follower;
  follower.replica.apply(rig.source.snapshot());
  med::ViewportSettings s = rig.settings();
  s.parameters = withBouncedLight("probes");
  auto raster = rig.registry.create(s, follower.contexts);  // kept: the pool holds what viewports hold
  raster->render(follower.replica, rig.view(follower.replica.scene()), follower.image);
  s.backend = "embree";
  s.parameters = {};
  auto traced = rig.registry.create(s, follower.contexts);
  EXPECT_EQ(traced->synchronize(follower.replica), med::SceneAdapter::Update::None)
      << "the rasterizer's bounced light converted the scene the path tracer's viewport shares";
}

TEST(BouncedLight, ABuildWithoutThePathTracerKeepsTheAmbientTerm) {
  // Only the rasterizer registered: asking for probes warns and lights as
  // the ambient term does, pixel for pixel.
  test::ViewportRig rig("vulkan", med::registerVulkan, "builtin:cornell", kSize);
  rig.source.commit();
  const auto render = [&](const std::string& mode) {
    test::Follower f;
    f.replica.apply(rig.source.snapshot());
    med::ViewportSettings s = rig.settings();
    s.parameters = withBouncedLight(mode);
    f.viewport = rig.registry.create(s, f.contexts);
    f.viewport->render(f.replica, rig.view(f.replica.scene()), f.image);
    return f.image;
  };
  const med::FrameBuffer asked = render("probes");
  EXPECT_EQ(test::differingPixels(asked, render("ambient")), 0u);
  CornellRig both;
  EXPECT_GT(test::differingPixels(asked, both.render("vulkan", withBouncedLight("probes"))), 0u)
      << "with the path tracer registered, probes change the picture";
}
