// Frame time of the Vulkan viewport at 1280x720 on built-in scenes once
// converted (sync of an empty change list, render, read-back), the figure
// issue 28 bounds: the look may cost at most twice the frame it had. The
// first frame (conversion, pipeline compilation) is left out.
#include <benchmark/benchmark.h>

#include "../../mediators/imported_scene.hpp"
#include "tsr/med/vulkan/register.hpp"
#include "tsr/sg/replica.hpp"

namespace {

void BM_VulkanFrame(benchmark::State& state, const char* name) {
  tsr::test::ImportedScene scene("vulkan", tsr::med::registerVulkan, name);
  tsr::sg::Replica replica;
  replica.apply(scene.source.commit());
  tsr::med::ContextPool contexts;
  auto viewport = scene.registry.create(scene.settings(), contexts);
  const tsr::med::View view = scene.view(replica.scene(), 1280, 720);
  tsr::med::FrameBuffer image;
  viewport->render(replica, view, image);
  for (auto _ : state) viewport->render(replica, view, image);
}

BENCHMARK_CAPTURE(BM_VulkanFrame, cornell, "builtin:cornell")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(3.0);
BENCHMARK_CAPTURE(BM_VulkanFrame, cornell_fog, "builtin:cornell-fog")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(3.0);

}  // namespace

BENCHMARK_MAIN();
