// The rasterizer and the path tracer agree on direct light: a scene where
// nothing shadows anything that the camera sees (the only light sits at the
// eye), rendered by the vulkan viewport and by the embree viewport with
// directOnly = true and many samples. Tolerances:
//  - colour: relMSE = mean over pixels and channels of (r - p)^2 / (p^2 + 0.01)
//    below 2e-3 on interior pixels (silhouette pixels, where the path
//    tracer's pixel-area average and MSAA's four samples legitimately
//    differ, are left out);
//  - depth: on the same pixels, within the depth change to the neighbouring
//    pixels (the path tracer keeps the nearest hit over the pixel's area,
//    MSAA the depth of sample 0, which is not the centre), plus 0.01 %.
#include <gtest/gtest.h>

#include <cmath>

#include <spdlog/spdlog.h>

#include "test_scenes.hpp"
#include "tsr/med/embree/register.hpp"
#include "tsr/med/vulkan/register.hpp"

using namespace tsr;

namespace {
constexpr std::uint32_t kSize = 64;
const sg::Vec3 kEye(0.0f, 1.6f, 5.0f);

struct Rig {
  sg::Scene source;
  sg::ContainerId root = sg::kNoContainer, camera = sg::kNoContainer;
  sg::Replica replica;
  med::ViewportRegistry registry;
  med::ContextPool contexts;
  Rig() {
    auto& group = source.create<sg::Group>("root");
    root = group.id();
    auto diffuse = [&](const char* name, sg::Vec3 c) {
      auto& m = source.create<sg::SurfaceMaterial>(name);
      m.setBaseColor(c);
      m.setMetallic(0.0f);
      m.setRoughness(1.0f);
      return m.id();
    };
    auto& metal = source.create<sg::SurfaceMaterial>("rough gold");
    metal.setBaseColor({0.9f, 0.7f, 0.3f});
    metal.setMetallic(1.0f);
    metal.setRoughness(0.5f);
    test::addQuad(source, root, "floor", {-3, 0, 3}, {3, 0, 3}, {3, 0, -3}, {-3, 0, -3},
                  diffuse("floor", {0.7f, 0.7f, 0.7f}));
    test::addQuad(source, root, "wall", {-3, 0, -3}, {3, 0, -3}, {3, 3, -3}, {-3, 3, -3},
                  diffuse("wall", {0.3f, 0.5f, 0.8f}));
    test::addSphere(source, root, "red sphere", {-0.9f, 0.7f, 0.0f}, 0.7f, 48, diffuse("red", {0.8f, 0.3f, 0.2f}));
    test::addSphere(source, root, "gold sphere", {0.9f, 0.7f, 0.0f}, 0.7f, 48, metal.id());
    // glTF's default material, white metal at roughness 1: most of what it
    // reflects of a light is multiple scattering.
    auto& roughMetal = source.create<sg::SurfaceMaterial>("glTF default");
    roughMetal.setBaseColor({1.0f, 1.0f, 1.0f});
    roughMetal.setMetallic(1.0f);
    roughMetal.setRoughness(1.0f);
    test::addSphere(source, root, "rough white metal", {0.0f, 2.1f, -1.6f}, 0.6f, 48, roughMetal.id());
    auto& light = source.create<sg::Light>("eye light");
    light.setKind(sg::LightKind::Point);
    light.setPosition(kEye);
    light.setIntensity(25.0f);
    group.addChild(light.id());
    auto& cam = source.create<sg::Camera>("camera");
    cam.lookAt(kEye, {0.0f, 0.8f, 0.0f});
    camera = cam.id();
    replica.apply(source.commit());
    med::registerVulkan(registry);
    med::registerEmbree(registry);
  }
  med::FrameBuffer render(const std::string& backend) {
    med::ViewportSettings s;
    s.backend = backend;
    s.root = root;
    if (backend == "embree") {
      s.parameters.set("directOnly", true);
      s.parameters.set("spp", std::int64_t{64});
      s.parameters.set("seed", std::int64_t{3});
    } else {
      s.parameters.set("msaa", std::int64_t{4});
      s.parameters.set("shadows", false);
      s.parameters.set("reflectionProbe", false);  // direct light only, as the path tracer's
      s.parameters.set("bouncedLight", std::string("ambient"));
    }
    med::FrameBuffer image;
    registry.create(s, contexts)
        ->render(replica, med::View::fromCamera(*replica.scene().find<sg::Camera>(camera), kSize, kSize), image);
    return image;
  }
};

// Pixels fully covered in both images, away from depth discontinuities.
std::vector<std::size_t> interiorPixels(const med::FrameBuffer& a, const med::FrameBuffer& b) {
  std::vector<std::size_t> out;
  for (std::uint32_t y = 1; y + 1 < a.height; ++y)
    for (std::uint32_t x = 1; x + 1 < a.width; ++x) {
      bool interior = true;
      const float d = a.depth[a.index(x, y)];
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          std::size_t n = a.index(x + static_cast<std::uint32_t>(dx), y + static_cast<std::uint32_t>(dy));
          interior &= a.colour[n].a == 1.0f && b.colour[n].a == 1.0f && std::abs(a.depth[n] - d) < 0.05f * d;
        }
      if (interior) out.push_back(a.index(x, y));
    }
  return out;
}
}  // namespace

TEST(CrossBackEnd, DirectLightAndDepthAgreeWithThePathTracer) {
  Rig rig;
  const med::FrameBuffer raster = rig.render("vulkan");
  const med::FrameBuffer traced = rig.render("embree");
  test::keepImage("vulkan_consistency_raster", raster);
  test::keepImage("vulkan_consistency_traced", traced);

  const auto pixels = interiorPixels(raster, traced);
  ASSERT_GT(pixels.size(), kSize * kSize / 2) << "most of the image is compared";
  double relMse = 0, meanDepthError = 0;
  std::size_t depthOutliers = 0;
  for (std::size_t i : pixels) {
    for (int c = 0; c < 3; ++c) {
      double r = raster.colour[i][c], p = traced.colour[i][c];
      relMse += (r - p) * (r - p) / (p * p + 0.01);
    }
    const double d = traced.depth[i], error = std::abs(double(raster.depth[i]) - d);
    double local = 0;  // how much depth changes over one pixel here
    const std::uint32_t x = static_cast<std::uint32_t>(i % kSize), y = static_cast<std::uint32_t>(i / kSize);
    for (std::uint32_t ny = y - 1; ny <= y + 1; ++ny)
      for (std::uint32_t nx = x - 1; nx <= x + 1; ++nx)
        local = std::max(local, std::abs(double(raster.depth[raster.index(nx, ny)]) - raster.depth[i]));
    depthOutliers += error > local + 1e-4 * d;
    meanDepthError += error / d;
  }
  relMse /= 3.0 * static_cast<double>(pixels.size());
  meanDepthError /= static_cast<double>(pixels.size());
  spdlog::info("vulkan vs embree direct only: relMSE {:.2e} over {} pixels, mean relative depth error {:.2e}", relMse,
               pixels.size(), meanDepthError);
  RecordProperty("relMSE", std::to_string(relMse));
  EXPECT_LT(relMse, 2e-3);
  EXPECT_EQ(depthOutliers, 0u) << "depth differs by more than one pixel's depth change";

  // The comparison can fail: a different light colour is far outside it.
  rig.source.find<sg::Light>(test::findNamed(rig.source, sg::ContainerType::Light, "eye light"))
      ->setColor({1.0f, 0.6f, 0.6f});
  rig.replica.apply(rig.source.commit());
  const med::FrameBuffer tinted = rig.render("vulkan");
  double tintedMse = 0;
  for (std::size_t i : pixels)
    for (int c = 0; c < 3; ++c) {
      double r = tinted.colour[i][c], p = traced.colour[i][c];
      tintedMse += (r - p) * (r - p) / (p * p + 0.01);
    }
  EXPECT_GT(tintedMse / (3.0 * static_cast<double>(pixels.size())), 10 * 2e-3);
}
