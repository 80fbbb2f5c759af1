// What streaming the merged scene by clusters (TraceMemory) costs the path
// tracer: rays/s of passes over a crowd of single-use meshes built whole,
// and streamed with budgets that hold all the clusters but one byte (what
// traversing clusters costs, with hardly a build), nine tenths, and a
// quarter (the rays of every pass reach more than it holds). Prints the
// ratios to the whole scene's rays/s measured in the same run.
#include "rays_per_second.hpp"
#include "test_scenes.hpp"

#include <benchmark/benchmark.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cstdio>
#include <map>
#include <string>

namespace {

using namespace tsr::embree;

// 40 x 40 balls of about 2,000 triangles each (3.2 M triangles), each its own
// mesh, on the floor under the lamp.
struct Crowd {
  Scene scene{test::sharedDevice()};
  Camera camera = Camera::lookAt({0, 3, 24}, {0, 0, 0}, {0, 1, 0}, glm::radians(50.0f), 1.0f);
  Crowd() {
    test::floorUnderLamp(scene);
    Material m;
    m.baseColor = glm::vec3(0.7f, 0.5f, 0.3f);
    const MaterialId id = scene.addMaterial(m);
    for (int i = 0; i < 40; ++i)
      for (int j = 0; j < 40; ++j)
        scene.addInstance(
            scene.addMesh(test::uvSphere({0, 0, 0}, 0.2f, 2000, true)), id,
            glm::translate(glm::mat4(1.0f), glm::vec3(-10.0f + 0.5f * float(j), 0.2f, -10.0f + 0.5f * float(i))));
    scene.commit();
  }
};

Crowd& crowd() {
  static Crowd c;
  return c;
}

// 0: whole; otherwise the budget as a fraction of the whole level's estimate.
void BM_Crowd(benchmark::State& state, double fraction) {
  Crowd& c = crowd();
  TraceMemory budget;
  if (fraction > 0.0) budget.bytes = std::uint64_t(fraction * double(c.scene.traceMemoryUse().wholeBytes));
  budget.clusterTriangles = 1u << 17;
  c.scene.setTraceMemory(budget);
  RenderSettings s;
  s.maxDepth = 4;
  Renderer renderer(s);
  const std::uint32_t size = 192;
  FrameBuffer fb(size, size);
  renderer.renderPass(c.scene, c.camera, Region::full(size, size), fb);  // the first pass builds what it reaches
  std::uint64_t rays = 0;
  const TraceMemoryUse before = c.scene.traceMemoryUse();
  for (auto _ : state) rays += renderer.renderPass(c.scene, c.camera, Region::full(size, size), fb).rays;
  const TraceMemoryUse after = c.scene.traceMemoryUse();
  state.counters["rays/s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
  state.counters["builds/pass"] =
      benchmark::Counter(double(after.builds - before.builds), benchmark::Counter::kAvgIterations);
  state.counters["clusters"] = after.clusters;
  c.scene.setTraceMemory(TraceMemory{});
}

BENCHMARK_CAPTURE(BM_Crowd, whole, 0.0)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK_CAPTURE(BM_Crowd, streamed_all_held, 0.999999)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK_CAPTURE(BM_Crowd, streamed_nine_tenths, 0.9)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK_CAPTURE(BM_Crowd, streamed_quarter, 0.25)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  tsr::bench::RaysPerSecond reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  const double whole = reporter.of("BM_Crowd/whole/");
  for (const auto& [name, rate] : reporter.rates)
    if (whole > 0.0 && !name.starts_with("BM_Crowd/whole/"))
      std::printf("%s: %.2fx the whole scene's rays/s\n", name.c_str(), rate / whole);
  benchmark::Shutdown();
  return 0;
}
