// Switching a window's back-end at run time: layers are switched on and off
// at no cost, and a viewport switched back on catches up through its
// change-log cursor instead of converting the scene again.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>

#include <spdlog/spdlog.h>
#include <glm/gtc/matrix_transform.hpp>

#include "test_scenes.hpp"
#include "tsr/med/embree/register.hpp"
#include "tsr/med/vulkan/register.hpp"
#include "tsr/med/window.hpp"
#include "tsr/sg/import/importer.hpp"

using namespace tsr;

namespace {
struct Rig {
  sg::Scene source;
  sg::ImportResult imported;
  sg::Replica replica;
  med::ViewportRegistry registry;
  med::ContextPool contexts;
  explicit Rig(const std::string& scene, std::size_t logCapacity = 256) : replica(logCapacity) {
    imported = sg::importScene(source, scene);
    replica.apply(source.commit());
    med::registerVulkan(registry);
    med::registerEmbree(registry);
  }
  std::unique_ptr<med::Viewport> viewport(const std::string& backend, med::ContextPool& pool) {
    med::ViewportSettings s;
    s.backend = backend;
    s.root = imported.root;
    s.background = imported.background;
    s.parameters.set("spp", std::int64_t{1});
    s.parameters.set("maxDepth", std::int64_t{2});
    // The rasterizer's own light: its bounced light would convert the path
    // tracer's scene before the path tracer's first use (bounced_light_test).
    s.parameters.set("bouncedLight", std::string("ambient"));
    s.parameters = registry.parametersFor(backend, s.parameters);  // the path tracer's, not the rasterizer's
    return registry.create(s, pool);
  }
  med::View view(std::uint32_t size) const {
    return med::View::fromCamera(*replica.scene().find<sg::Camera>(imported.cameras.front()), size, size);
  }
  // One frame of an animation: `count` objects move; the replica follows.
  void animate(int frame, std::size_t count) {
    const auto& children = source.find<sg::Group>(imported.root)->children();
    std::size_t moved = 0;
    for (auto child : children) {
      auto* t = source.find<sg::Transform>(child);
      if (!t) continue;
      if (moved++ == count) break;
      t->setMatrix(glm::translate(t->matrix(), glm::vec3(0, 0.001f * static_cast<float>(frame % 7), 0)));
    }
    replica.apply(source.commit());
  }
};

template <class F>
double secondsOf(F&& f) {
  const auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

TEST(Switching, WindowShowsOnlyTheActiveLayer) {
  Rig rig("builtin:animated");
  med::Window window;
  auto& raster = window.addLayer(rig.viewport("vulkan", rig.contexts));
  auto& traced = window.addLayer(rig.viewport("embree", rig.contexts));
  const auto view = rig.view(48);
  med::FrameBuffer alone;

  traced.setActive(false);  // navigate with the rasterizer
  auto image = window.render(rig.replica, view);
  rig.viewport("vulkan", rig.contexts)->render(rig.replica, view, alone);
  EXPECT_EQ(test::differingPixels(image, alone), 0u);
  EXPECT_EQ(window.lastStats()[1].update, med::SceneAdapter::Update::None);
  EXPECT_EQ(window.lastStats()[1].seconds, 0.0) << "an inactive layer costs nothing";

  rig.animate(1, 3);
  raster.setActive(false);  // then path trace from here
  traced.setActive(true);
  image = window.render(rig.replica, view);
  EXPECT_EQ(window.lastStats()[1].update, med::SceneAdapter::Update::Converted) << "first use of the path tracer";
  EXPECT_EQ(window.lastStats()[0].seconds, 0.0);
  rig.viewport("embree", rig.contexts)->render(rig.replica, view, alone);
  EXPECT_EQ(test::differingPixels(image, alone), 0u);

  rig.animate(2, 3);
  raster.setActive(true);  // and back: the rasterizer catches up
  traced.setActive(false);
  image = window.render(rig.replica, view);
  EXPECT_EQ(window.lastStats()[0].update, med::SceneAdapter::Update::Synced);
  rig.viewport("vulkan", rig.contexts)->render(rig.replica, view, alone);
  EXPECT_EQ(test::differingPixels(image, alone), 0u);
}

TEST(Switching, ViewportFallenOutOfTheLogConvertsAgain) {
  Rig rig("builtin:instances:50", 16);
  med::ContextPool pool;
  auto viewport = rig.viewport("vulkan", pool);
  EXPECT_EQ(viewport->synchronize(rig.replica), med::SceneAdapter::Update::Converted);
  viewport->setActive(false);
  for (int frame = 0; frame < 40; ++frame) rig.animate(frame, 1);
  viewport->setActive(true);
  EXPECT_EQ(viewport->synchronize(rig.replica), med::SceneAdapter::Update::Converted);
}

// The one timing comparison the issue asks for: switching a converted
// viewport back on after 100 animated frames must cost under 1 % of
// converting the scene. Minimum of several repetitions against noise.
TEST(Switching, ReactivationCostsUnderOnePercentOfAConversion) {
  Rig rig("builtin:instances:10000");
  constexpr int kRepetitions = 5;
  for (const std::string backend : {"vulkan", "embree"}) {
    double conversion = 1e30, activation = 1e30;
    for (int rep = 0; rep < kRepetitions; ++rep) {
      med::ContextPool pool;  // nothing shared: a full conversion
      auto fresh = rig.viewport(backend, pool);
      med::SceneAdapter::Update update{};
      conversion = std::min(conversion, secondsOf([&] { update = fresh->synchronize(rig.replica); }));
      ASSERT_EQ(update, med::SceneAdapter::Update::Converted);
    }
    med::ContextPool pool;
    auto viewport = rig.viewport(backend, pool);
    ASSERT_EQ(viewport->synchronize(rig.replica), med::SceneAdapter::Update::Converted);
    for (int rep = 0; rep < kRepetitions; ++rep) {
      viewport->setActive(false);
      for (int frame = 0; frame < 100; ++frame) rig.animate(frame, 5);
      viewport->setActive(true);
      med::SceneAdapter::Update update{};
      activation = std::min(activation, secondsOf([&] { update = viewport->synchronize(rig.replica); }));
      ASSERT_EQ(update, med::SceneAdapter::Update::Synced);
    }
    const double ratio = activation / conversion;
    spdlog::info("{}: conversion {:.3f} ms, activation after 100 frames {:.4f} ms, ratio {:.5f}", backend,
                 conversion * 1e3, activation * 1e3, ratio);
    RecordProperty(backend + "_switch_ratio", std::to_string(ratio));
    EXPECT_LT(ratio, 0.01) << backend;
  }
}
