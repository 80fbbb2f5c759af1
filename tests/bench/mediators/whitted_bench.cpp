// A Whitted frame (mode=whitted, Schwenk's figure 5.6 middle renderer) of
// builtin:cornell at 1280x720 through a real Embree viewport, as a viewer
// gets it the moment the camera rests: each iteration is a new pose (two
// poses a hair apart, alternating), so every pixel is traced anew. The
// issue's target is 0.2 s a frame on this machine's two cores.
#include <memory>

#include <benchmark/benchmark.h>

#include "../../mediators/imported_scene.hpp"
#include "tsr/med/context_pool.hpp"
#include "tsr/med/embree/register.hpp"
#include "tsr/sg/replica.hpp"

using namespace tsr;

namespace {

void BM_WhittedFrame(benchmark::State& state) {
  med::Parameters p;
  p.set("mode", std::string("whitted"));
  test::ImportedScene s("embree", med::registerEmbree, "builtin:cornell", p);
  s.source.commit();
  sg::Replica replica(4);
  replica.apply(s.source.snapshot());
  med::ContextPool contexts;
  auto viewport = s.registry.create(s.settings(), contexts);
  const auto width = std::uint32_t(state.range(0)), height = std::uint32_t(state.range(1));
  med::View poses[2] = {s.view(replica.scene(), width, height), s.view(replica.scene(), width, height)};
  poses[1].cameraToWorld[3].x += 1e-4f;
  med::FrameBuffer out;
  viewport->render(replica, poses[0], out);  // converts the scene and builds its BVH, once
  int i = 0;
  std::uint64_t rays = 0;
  for (auto _ : state) rays += viewport->render(replica, poses[++i % 2], out).rays;
  state.counters["Mrays/s"] = benchmark::Counter(double(rays) * 1e-6, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_WhittedFrame)->Args({1280, 720})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
