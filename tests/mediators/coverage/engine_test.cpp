// The coverage viewport's two engines, the Embree ray-traced id pass and the
// Vulkan rasterised one, agree on the same scene. Both sample pixel centres,
// so they differ only where a triangle edge passes (within rounding) through
// a centre. Stated tolerances: at least 99 % of pixels show the same id,
// depths agree within 0.1 % where the ids do, and every object's pixel
// count agrees within 2 % of it plus 3 pixels.
#include <gtest/gtest.h>

#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include "tsr/med/coverage/ranking.hpp"
#include "tsr/med/coverage/register.hpp"
#include "tsr/med/vulkan/register.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/vk/shared_device.hpp"

using namespace tsr;

namespace {
struct Engines {
  sg::Scene source;
  sg::ImportResult imported;
  sg::Replica replica;
  med::ViewportRegistry registry;
  med::ContextPool contexts;
  explicit Engines(const std::string& scene) {
    imported = sg::importScene(source, scene);
    replica.apply(source.commit());
    med::registerCoverage(registry);
  }
  med::FrameBuffer render(const std::string& engine, std::unique_ptr<med::Viewport>& viewport) {
    if (!viewport) {
      med::ViewportSettings s;
      s.backend = "coverage";
      s.root = imported.root;
      s.parameters.set("engine", engine);
      viewport = registry.create(s, contexts);
    }
    med::FrameBuffer image;
    viewport->render(replica,
                     med::View::fromCamera(*replica.scene().find<sg::Camera>(imported.cameras.front()), 96, 96), image);
    return image;
  }
};

void expectAgreement(const med::FrameBuffer& traced, const med::FrameBuffer& raster, const sg::Scene& scene,
                     const char* what) {
  const auto& a = traced.outputs.at(med::kIdOutput);
  const auto& b = raster.outputs.at(med::kIdOutput);
  ASSERT_EQ(a.size(), b.size());
  std::size_t same = 0, depthOff = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] != b[i]) continue;
    ++same;
    if (std::isfinite(traced.depth[i]) && std::abs(traced.depth[i] - raster.depth[i]) > 1e-3f * traced.depth[i])
      ++depthOff;
  }
  EXPECT_GE(same, a.size() * 99 / 100) << what;
  EXPECT_EQ(depthOff, 0u) << what;
  std::map<sg::ContainerId, std::uint64_t> rasterPixels;
  for (const auto& o : med::rankObjects(raster, scene)) rasterPixels[o.id] = o.pixels;
  const auto ranked = med::rankObjects(traced, scene);
  ASSERT_GT(ranked.size(), 3u) << what;
  for (const auto& o : ranked)
    EXPECT_LE(std::abs(double(o.pixels) - double(rasterPixels[o.id])), 0.02 * double(o.pixels) + 3)
        << what << " " << o.id;
  EXPECT_EQ(med::backgroundPixels(traced) > 0, med::backgroundPixels(raster) > 0) << what;
}
}  // namespace

TEST(CoverageEngines, EmbreeAndVulkanAgreeOnInstances) {
  Engines rig("builtin:instances:300");
  std::unique_ptr<med::Viewport> embree, vulkan;
  expectAgreement(rig.render("embree", embree), rig.render("vulkan", vulkan), rig.replica.scene(), "instances");

  // After an edit both catch up incrementally and still agree.
  const auto& children = rig.source.find<sg::Group>(rig.imported.root)->children();
  int moved = 0;
  for (auto child : children)
    if (auto* t = rig.source.find<sg::Transform>(child); t && moved++ < 20)
      t->setMatrix(glm::translate(t->matrix(), glm::vec3(0.3f, 0.2f, 0)));
  rig.replica.apply(rig.source.commit());
  expectAgreement(rig.render("embree", embree), rig.render("vulkan", vulkan), rig.replica.scene(), "after moving 20");
}

TEST(CoverageEngines, TransparentGlassIsLeftOutByBoth) {
  Engines rig("builtin:cornell");  // the glass sphere is transparent
  std::unique_ptr<med::Viewport> embree, vulkan;
  const auto traced = rig.render("embree", embree);
  const auto raster = rig.render("vulkan", vulkan);
  expectAgreement(traced, raster, rig.replica.scene(), "cornell");
  for (const auto& o : med::rankObjects(raster, rig.replica.scene()))
    EXPECT_EQ(o.name.find("glass"), std::string::npos) << "glass is not counted";
}

TEST(CoverageEngines, UnknownEngineIsAParameterError) {
  Engines rig("builtin:cornell");
  med::ViewportSettings s;
  s.backend = "coverage";
  s.parameters.set("engine", std::string("optix"));
  EXPECT_THROW(rig.registry.create(s, rig.contexts), med::ParameterError);
}

// A layered coverage + Vulkan render opens one device: the rasterizer's
// context and the Vulkan id pass both hold the process's.
TEST(CoverageEngines, VulkanIdPassSharesTheRasterizersDevice) {
  auto held = vk::sharedDevice();
  const long before = held.use_count();
  Engines rig("builtin:cornell");
  med::registerVulkan(rig.registry);
  std::unique_ptr<med::Viewport> ids;
  rig.render("vulkan", ids);
  med::ViewportSettings s;
  s.backend = "vulkan";
  s.root = rig.imported.root;
  auto raster = rig.registry.create(s, rig.contexts);
  med::FrameBuffer image;
  raster->render(rig.replica,
                 med::View::fromCamera(*rig.replica.scene().find<sg::Camera>(rig.imported.cameras.front()), 32, 32),
                 image);
  EXPECT_EQ(held.use_count(), before + 2) << "one device for both, not one each";
}
