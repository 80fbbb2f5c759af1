// Frame time of the Vulkan viewport at 1280x720 on built-in scenes once
// converted (sync of an empty change list, render, read-back), the figure
// issue 28 bounds: the look may cost at most twice the frame it had. The
// first frame (conversion, pipeline compilation) is left out.
//
// With the path tracer in the build (issue 46): the same frame lit by its
// bounced light (bouncedLight=probes, every probe traced) against the
// ambient term, and how long the probes take to be traced again after one
// object moves in the viewer (frames and seconds, at the default
// probesPerFrame).
#include <benchmark/benchmark.h>

#include "../../mediators/imported_scene.hpp"
#include "tsr/med/vulkan/register.hpp"
#include "tsr/sg/replica.hpp"
#include "vulkan_viewport.hpp"
#if TSR_LOOK_BENCH_EMBREE
#include "tsr/med/embree/register.hpp"
#endif

#include <chrono>

namespace {

void registerBackends(tsr::med::ViewportRegistry& registry) {
  tsr::med::registerVulkan(registry);
#if TSR_LOOK_BENCH_EMBREE
  tsr::med::registerEmbree(registry);
#endif
}

tsr::med::Parameters bouncedLight(const char* mode) {
  tsr::med::Parameters p;
  p.set("bouncedLight", std::string(mode));
  return p;
}

void BM_VulkanFrame(benchmark::State& state, const char* name, const char* mode) {
  tsr::test::ImportedScene scene("vulkan", registerBackends, name, bouncedLight(mode));
  tsr::sg::Replica replica;
  replica.apply(scene.source.commit());
  tsr::med::ContextPool contexts;
  auto viewport = scene.registry.create(scene.settings(), contexts);
  const tsr::med::View view = scene.view(replica.scene(), 1280, 720);
  tsr::med::FrameBuffer image;
  viewport->render(replica, view, image);  // converts, and traces every probe
  auto& vulkan = dynamic_cast<tsr::med::vulkan_mediator::VulkanViewport&>(*viewport);
  double redrawn = 0;  // reflection probes drawn again: none once the scene rests
  for (auto _ : state) {
    viewport->render(replica, view, image);
    redrawn += vulkan.lastFrame().probes;
  }
  state.counters["reflectionProbes"] = benchmark::Counter(redrawn, benchmark::Counter::kAvgIterations);
}

#if TSR_LOOK_BENCH_EMBREE
// Moves the mirror sphere and renders until every probe was traced again.
void BM_ProbesAfterAnEdit(benchmark::State& state) {
  tsr::test::ImportedScene scene("vulkan", registerBackends, "builtin:cornell", bouncedLight("probes"));
  tsr::sg::Replica replica;
  replica.apply(scene.source.commit());
  tsr::med::ContextPool contexts;
  auto viewport = scene.registry.create(scene.settings(), contexts);
  auto& vulkan = dynamic_cast<tsr::med::vulkan_mediator::VulkanViewport&>(*viewport);
  const tsr::med::View view = scene.view(replica.scene(), 1280, 720);
  tsr::med::FrameBuffer image;
  tsr::med::RenderControl interactive;  // as the viewer renders: probes traced again in turns
  interactive.interactive = true;
  viewport->render(replica, view, image, interactive);
  tsr::sg::ContainerId sphere = tsr::sg::kNoContainer;
  for (auto id : scene.source.ids())
    if (scene.source.find(id)->type() == tsr::sg::ContainerType::Transform &&
        scene.source.find(id)->name() == "mirror sphere")
      sphere = id;
  if (sphere == tsr::sg::kNoContainer) {
    state.SkipWithError("no mirror sphere");
    return;
  }
  float step = -150.0f;
  double frames = 0;
  for (auto _ : state) {
    auto& t = *scene.source.find<tsr::sg::Transform>(sphere);
    tsr::sg::Mat4 m = t.matrix();
    m[3][0] += step;
    step = -step;
    t.setMatrix(m);
    replica.apply(scene.source.commit());
    const auto start = std::chrono::steady_clock::now();
    do {
      viewport->render(replica, view, image, interactive);
      ++frames;
    } while (vulkan.staleProbes() > 0);
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  state.counters["frames"] = benchmark::Counter(frames, benchmark::Counter::kAvgIterations);
}
#endif

BENCHMARK_CAPTURE(BM_VulkanFrame, cornell, "builtin:cornell", "ambient")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(3.0);
BENCHMARK_CAPTURE(BM_VulkanFrame, cornell_fog, "builtin:cornell-fog", "ambient")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(3.0);
#if TSR_LOOK_BENCH_EMBREE
BENCHMARK_CAPTURE(BM_VulkanFrame, cornell_probes, "builtin:cornell", "probes")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(3.0);
BENCHMARK(BM_ProbesAfterAnEdit)->Unit(benchmark::kMillisecond)->UseManualTime()->Iterations(4);
#endif

}  // namespace

BENCHMARK_MAIN();
