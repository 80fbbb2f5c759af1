// Hybrid rendering: the path-traced Cornell box with a rasterised marker on
// top, two back-ends layered in one window and composited by depth. The
// marker sits partly behind a block, so the path tracer must hide that part.
#include <gtest/gtest.h>

#include "test_scenes.hpp"
#include "tsr/med/embree/register.hpp"
#include "tsr/med/vulkan/register.hpp"
#include "tsr/med/window.hpp"
#include "tsr/sg/import/importer.hpp"

using namespace tsr;

namespace {
constexpr std::uint32_t kSize = 96;

// The pixel a world point falls in.
glm::ivec2 pixelOf(const med::View& view, glm::vec3 world) {
  glm::vec3 c = glm::vec3(glm::inverse(view.cameraToWorld) * glm::vec4(world, 1.0f));
  float x = -view.nearPlane * c.x / c.z, y = -view.nearPlane * c.y / c.z;
  return {static_cast<int>((x - view.left) / (view.right - view.left) * static_cast<float>(view.width)),
          static_cast<int>((view.top - y) / (view.top - view.bottom) * static_cast<float>(view.height))};
}

struct HybridRig {
  sg::Scene source;
  sg::ImportResult imported;
  sg::ContainerId markers = sg::kNoContainer;
  sg::Replica replica;
  med::ViewportRegistry registry;
  med::ContextPool contexts;
  HybridRig() {
    imported = sg::importScene(source, "builtin:cornell");
    // The marker: small, bright, self-lit geometry under its own root, behind
    // the tall block's right side (world +x, which the camera at z = -800
    // looking down +z sees on its left), poking out past it.
    auto& group = source.create<sg::Group>("markers");
    markers = group.id();
    auto& glow = source.create<sg::SurfaceMaterial>("marker green");
    glow.setBaseColor({0, 0, 0});
    glow.setEmission({0.05f, 1.0f, 0.1f});
    glow.setEmissionStrength(1.5f);
    test::addBox(source, markers, "marker", {440, 150, 490}, {530, 230, 530}, glow.id());
    replica.apply(source.commit());
    med::registerEmbree(registry);
    med::registerVulkan(registry);
  }
  std::unique_ptr<med::Viewport> pathTracer() {
    med::ViewportSettings s;
    s.backend = "embree";
    s.root = imported.root;
    s.background = imported.background;
    s.parameters.set("spp", std::int64_t{4});
    s.parameters.set("maxDepth", std::int64_t{3});
    return registry.create(s, contexts);
  }
  std::unique_ptr<med::Viewport> rasterizer() {
    med::ViewportSettings s;
    s.backend = "vulkan";
    s.root = markers;
    return registry.create(s, contexts);
  }
  med::View view() const {
    return med::View::fromCamera(*replica.scene().find<sg::Camera>(imported.cameras.front()), kSize, kSize);
  }
};
}  // namespace

TEST(Hybrid, RasterisedMarkerIsOccludedByPathTracedGeometry) {
  HybridRig rig;
  med::Window window;
  window.addLayer(rig.pathTracer());
  window.addLayer(rig.rasterizer());
  const med::View view = rig.view();
  const med::FrameBuffer hybrid = window.render(rig.replica, view);

  med::FrameBuffer traced, marker;
  rig.pathTracer()->render(rig.replica, view, traced);
  rig.rasterizer()->render(rig.replica, view, marker);
  test::keepImage("vulkan_hybrid", hybrid);
  test::keepImage("vulkan_hybrid_marker_only", marker);

  const glm::ivec2 visible = pixelOf(view, {515, 190, 490});   // the marker's part beside the tall block
  const glm::ivec2 occluded = pixelOf(view, {455, 190, 490});  // its part behind it
  for (glm::ivec2 p : {visible, occluded}) {
    ASSERT_GE(p.x, 0);
    ASSERT_LT(p.x, static_cast<int>(kSize));
    std::size_t i = marker.index(static_cast<std::uint32_t>(p.x), static_cast<std::uint32_t>(p.y));
    EXPECT_EQ(marker.colour[i].a, 1.0f) << "the marker covers both pixels on its own";
    EXPECT_GT(marker.colour[i].g, 1.0f) << "bright green";
  }
  auto at = [&](const med::FrameBuffer& fb, glm::ivec2 p) {
    return fb.colour[fb.index(static_cast<std::uint32_t>(p.x), static_cast<std::uint32_t>(p.y))];
  };
  auto index = [&](glm::ivec2 p) {
    return marker.index(static_cast<std::uint32_t>(p.x), static_cast<std::uint32_t>(p.y));
  };
  EXPECT_GT(traced.depth[index(visible)], marker.depth[index(visible)]) << "the back wall is behind the marker";
  EXPECT_LT(traced.depth[index(occluded)], marker.depth[index(occluded)]) << "the block is in front of it";
  // Visible: marker colour over the back wall; occluded: the path-traced block.
  EXPECT_EQ(at(hybrid, visible), at(marker, visible));
  EXPECT_EQ(at(hybrid, occluded), at(traced, occluded));
  EXPECT_NE(at(hybrid, occluded), at(marker, occluded));

  // Everywhere: a pixel shows the marker only where the marker is nearer.
  std::size_t markerPixels = 0, hidden = 0;
  for (std::size_t i = 0; i < hybrid.colour.size(); ++i) {
    if (marker.colour[i].a < 1.0f) {
      EXPECT_EQ(hybrid.colour[i], traced.colour[i]) << "no marker here: the path-traced image unchanged";
      continue;
    }
    ++markerPixels;
    const bool markerNearer = marker.depth[i] <= traced.depth[i];
    hidden += !markerNearer;
    EXPECT_EQ(hybrid.colour[i], markerNearer ? marker.colour[i] : traced.colour[i]) << i;
  }
  EXPECT_GT(markerPixels, 20u);
  EXPECT_GT(hidden, 5u) << "part of the marker is behind the block";
  EXPECT_LT(hidden, markerPixels - 5) << "part of it is in front of the back wall";
}
