// Filtered path tracing through real nodes: pixel filtering and the
// denoiser gather from neighbours many pixels away, so cooperative tiles are resolved on the
// client after assembly and must show no seams; radiance filtering traces
// tiles with a halo and matches within a stated tolerance.
#include <cmath>

#include <gtest/gtest.h>

#include "cluster_test_util.hpp"
#include "tsr/cluster/cluster_window.hpp"
#include "tsr/med/embree/register.hpp"
#include "tsr/med/viewport_registry.hpp"
#include "tsr/sg/replica.hpp"

namespace tsr::cluster::test {
namespace {

using namespace std::chrono_literals;
constexpr std::uint32_t kSize = 64;

med::Parameters filtered(const std::string& mode) {
  med::Parameters p;
  p.set("spp", std::int64_t{8});
  p.set("maxDepth", std::int64_t{4});
  p.set("seed", std::int64_t{3});
  p.set("threads", std::int64_t{1});
  p.set("filter", mode);
  return p;
}

struct FilteredSession {
  AnimatedScene s;
  sg::Replica replica;
  med::ViewportRegistry registry;
  med::ContextPool contexts;
  std::unique_ptr<med::Viewport> local;
  std::unique_ptr<ClusterWindow> window;

  FilteredSession(ClusterConfig config, const med::Parameters& parameters, const std::string& scene = "builtin:cornell")
      : s(scene) {
    med::registerEmbree(registry);
    local = registry.create({"embree", s.imported.root, s.imported.background, parameters, true}, contexts);
    ClientOptions options;
    options.registry = &registry;
    window = std::make_unique<ClusterWindow>(std::move(config), options);
    window->setContent(s.imported.root, s.imported.background);
    auto delta = s.scene.commit();
    replica.apply(delta);
    EXPECT_EQ(window->connect(5s), window->config().nodes.size());
    window->publish(s.scene, delta);
  }
  med::View view() const {
    return med::View::fromCamera(*s.scene.find<sg::Camera>(s.imported.cameras.front()), kSize, kSize);
  }
  med::FrameBuffer localImage() {
    med::FrameBuffer fb;
    local->render(replica, view(), fb);
    return fb;
  }
};

// The largest relative difference of colour over all pixels.
float largestDifference(const med::FrameBuffer& a, const med::FrameBuffer& b) {
  float worst = 0.0f;
  for (std::size_t i = 0; i < a.colour.size(); ++i)
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(a.colour[i][c] - b.colour[i][c]) / (std::abs(b.colour[i][c]) + 0.01f));
  return worst;
}

// Pixel filtering and the whole-image denoiser (filter=denoise) reach many
// pixels across tile borders: their inputs travel with the tiles and the
// client resolves the assembled frame, equal to the local filtered image.
TEST(ClusterFilter, FilteredCooperativeTilesEqualTheLocalFilteredImage) {
  for (const char* mode : {"pixel", "denoise"}) {
    auto nodes = startNodes(2);
    ClusterConfig c = configFor(ClusterMode::Cooperative, nodes, filtered(mode));
    c.cooperative.tileSize = 16;  // many tile borders for a seam to show at
    FilteredSession app(c, filtered(mode));
    ClusterFrame f = app.window->render(app.view());
    med::FrameBuffer reference = app.localImage();
    EXPECT_TRUE(bitwiseEqual(f.image, reference))
        << mode << ": largest difference " << largestDifference(f.image, reference);
    EXPECT_TRUE(f.image.outputs.empty()) << mode << ": the filter's inputs stay on the client";
  }
}

// Media travel to the nodes (volume materials, their 3D textures, the
// background's fog) and trace there as here: cooperative tiles of a foggy
// scene whose milk is textured (delta tracking), unfiltered and
// pixel-filtered, equal the local image bit for bit.
TEST(ClusterFilter, FoggyCooperativeTilesEqualTheLocalImage) {
  for (const char* mode : {"none", "pixel"}) {
    auto nodes = startNodes(2);
    ClusterConfig c = configFor(ClusterMode::Cooperative, nodes, filtered(mode));
    c.cooperative.tileSize = 16;
    FilteredSession app(c, filtered(mode), "builtin:cornell-fog");
    auto& density = app.s.scene.create<sg::Image>("density");
    density.setPixels(2, 4, 1, sg::PixelFormat::UInt8, {255, 40, 255, 40, 90, 0, 90, 0});
    density.setColorSpace(sg::ColorSpace::Linear);
    std::size_t textured = 0;
    for (sg::ContainerId id : app.s.scene.ids())
      if (auto* v = app.s.scene.find<sg::VolumeMaterial>(id);
          v && app.s.scene.find<sg::Background>(app.s.imported.background)->medium() != id) {
        v->setScatteringTexture(density.id());
        v->setTextureSlices(2);
        ++textured;
      }
    ASSERT_EQ(textured, 1u) << "the milk";
    auto delta = app.s.scene.commit();
    app.replica.apply(delta);
    app.window->publish(app.s.scene, delta);
    ClusterFrame f = app.window->render(app.view());
    med::FrameBuffer reference = app.localImage();
    EXPECT_TRUE(bitwiseEqual(f.image, reference))
        << mode << ": largest difference " << largestDifference(f.image, reference);
  }
}

TEST(ClusterFilter, WithoutResolvingOnTheClientTilesWouldShowSeams) {
  // The same render with nodes filtering their own tiles differs from the
  // local image: what the client-side resolve is there for.
  auto nodes = startNodes(2);
  ClusterConfig c = configFor(ClusterMode::Cooperative, nodes, filtered("pixel"));
  c.cooperative.tileSize = 16;
  FilteredSession app(c, filtered("pixel"));
  ClusterWindow own(c);
  own.setContent(app.s.imported.root, app.s.imported.background);
  ASSERT_EQ(own.connect(5s), 2u);
  own.publish(app.s.scene, nullptr);
  ClusterFrame f = own.render(app.view());
  EXPECT_FALSE(bitwiseEqual(f.image, app.localImage()));
}

TEST(ClusterFilter, RadianceFilteredTilesWithHaloMatchWithinTolerance) {
  auto nodes = startNodes(2);
  ClusterConfig c = configFor(ClusterMode::Cooperative, nodes, filtered("radiance"));
  c.cooperative.tileSize = 32;
  FilteredSession app(c, filtered("radiance"));
  ClusterFrame f = app.window->render(app.view());
  med::FrameBuffer reference = app.localImage();
  // Variance estimates are filtered across tile borders and feed the next
  // frame's radius, so the halo bounds but does not remove the influence
  // of pixels outside it (backends/embree/README.md).
  double meanError = 0.0;
  for (std::size_t i = 0; i < reference.colour.size(); ++i)
    for (int ch = 0; ch < 3; ++ch)
      meanError +=
          std::abs(f.image.colour[i][ch] - reference.colour[i][ch]) / (std::abs(reference.colour[i][ch]) + 0.01);
  meanError /= 3.0 * reference.colour.size();
  EXPECT_LT(meanError, 0.01);
}

}  // namespace
}  // namespace tsr::cluster::test
