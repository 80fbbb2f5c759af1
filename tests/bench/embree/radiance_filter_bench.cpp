// One 512x512 radiance-filtering pass against one 1-spp path tracing pass on
// the plain Cornell box (tests/bench/scenes/make_cornell.py, no sphere). The
// radiance pass is timed at frame 1 (warm-up radius, the widest kernels)
// and at frame 8 (radii from the variance estimate).
#include "test_scenes.hpp"

#include <benchmark/benchmark.h>
#include <oneapi/tbb/task_arena.h>

#include <chrono>
#include <thread>

namespace {

using namespace tsr::embree;

constexpr std::uint32_t kSize = 512;

struct Bench {
  Scene scene{test::sharedDevice()};
  Camera camera;
  Bench() {
    camera = test::cornellBox(scene, 0);
    scene.commit();
    std::this_thread::sleep_for(std::chrono::seconds(1));  // TBB workers spin after a build
  }
};

Bench& bench() {
  static Bench b;
  return b;
}

RenderSettings settings() {
  RenderSettings s;
  s.threads = tbb::info::default_concurrency();
  return s;
}

void BM_PathTracerPass(benchmark::State& state) {
  Bench& b = bench();
  Renderer renderer(settings());
  FrameBuffer fb(kSize, kSize);
  for (auto _ : state) renderer.renderPass(b.scene, b.camera, Region::full(kSize, kSize), fb);
}

// Frame `state.range(0)` of a fresh radiance-filtered image.
void BM_RadiancePass(benchmark::State& state) {
  Bench& b = bench();
  Renderer renderer(settings());
  FrameBuffer fb(kSize, kSize);
  RadianceAccumulator acc(kSize, kSize);
  const Region region = Region::full(kSize, kSize);
  const int frame = int(state.range(0));
  for (auto _ : state) {
    state.PauseTiming();
    fb.reset();
    for (int i = 1; i < frame; ++i) renderer.renderRadiancePass(b.scene, b.camera, region, fb, acc);
    state.ResumeTiming();
    renderer.renderRadiancePass(b.scene, b.camera, region, fb, acc);
  }
}

BENCHMARK(BM_PathTracerPass)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
BENCHMARK(BM_RadiancePass)->Arg(1)->Arg(8)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);

}  // namespace

BENCHMARK_MAIN();
