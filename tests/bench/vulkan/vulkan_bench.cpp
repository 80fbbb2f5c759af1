// Frame time of the Vulkan back-end on 10,000 instances of three shared
// meshes at 1920x1080 (render + readback of colour and depth), against a
// minimal Vulkan program drawing the same triangles with a trivial shader.
// The ratio of the two is printed at the end; the target is <= 1.3.

#include "bench_scene.hpp"
#include "minimal_renderer.hpp"

#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"

#include <benchmark/benchmark.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cstdio>
#include <map>
#include <memory>
#include <string>

namespace tsr::vk::bench {
namespace {

constexpr std::uint32_t kWidth = 1920;
constexpr std::uint32_t kHeight = 1080;
constexpr std::uint32_t kInstances = 10000;

struct Fixture {
  std::shared_ptr<Device> device = Device::create();
  BenchScene content = makeBenchScene(kInstances, kWidth, kHeight);
  Scene scene{device};
  MinimalRenderer minimal{device, content, kWidth, kHeight};

  Fixture() {
    std::vector<MeshId> meshes;
    for (const MeshData& m : content.meshes) meshes.push_back(scene.addMesh(m));
    std::vector<MaterialId> materials;
    for (glm::vec3 c : {glm::vec3(0.8f, 0.3f, 0.2f), glm::vec3(0.2f, 0.7f, 0.3f), glm::vec3(0.3f, 0.4f, 0.9f)}) {
      Material mat;
      mat.baseColor = c;
      materials.push_back(scene.addMaterial(mat));
    }
    for (std::size_t i = 0; i < content.instanceMesh.size(); ++i)
      scene.addInstance(meshes[content.instanceMesh[i]], materials[content.instanceMesh[i]],
                        content.instanceTransform[i]);
    scene.addLight(DirectionalLight{{0.3f, -1.0f, -0.4f}, glm::vec3(2.0f)});
    scene.addLight(PointLight{{0.0f, 20.0f, 20.0f}, glm::vec3(400.0f)});
    scene.setEnvironment(Environment::constant(glm::vec3(0.05f)));
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

void BM_MinimalVulkan(benchmark::State& state) {
  Fixture& f = fixture();
  for (auto _ : state) {
    f.minimal.renderFrame();
    benchmark::DoNotOptimize(f.minimal.colour().data());
  }
  state.counters["tris/s"] =
      benchmark::Counter(double(f.content.trianglesPerFrame()), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_TesseraVulkan(benchmark::State& state) {
  Fixture& f = fixture();
  RenderSettings settings;
  settings.msaaSamples = std::uint32_t(state.range(0));
  settings.shadows = state.range(1) != 0;
  settings.shadowMapSize = 2048;
  Renderer renderer(f.device, settings);
  FrameBuffer fb(kWidth, kHeight);
  renderer.render(f.scene, f.content.camera, Region::full(kWidth, kHeight), fb);  // pipelines, targets
  for (auto _ : state) {
    renderer.render(f.scene, f.content.camera, Region::full(kWidth, kHeight), fb);
    benchmark::DoNotOptimize(fb.colourImage().data());
  }
  state.counters["tris/s"] =
      benchmark::Counter(double(renderer.lastStats().triangles), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["draws"] = renderer.lastStats().drawCalls;
}

BENCHMARK(BM_MinimalVulkan)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_TesseraVulkan)
    ->ArgNames({"msaa", "shadows"})
    ->Args({1, 0})
    ->Args({1, 1})
    ->Args({4, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

// A frame after one edit, with shadows: one instance in the middle of the
// grid moved back and forth (its shadow footprint drawn again) against a
// material edit (every caster drawn again). Shadow triangles a frame are the
// counter to compare.
void BM_FrameAfterAnEdit(benchmark::State& state) {
  Fixture& f = fixture();
  RenderSettings settings;
  settings.shadowMapSize = 2048;
  Renderer renderer(f.device, settings);
  FrameBuffer fb(kWidth, kHeight);
  renderer.render(f.scene, f.content.camera, Region::full(kWidth, kHeight), fb);
  const auto middle = InstanceId(kInstances / 2 + 50);
  const glm::mat4 at = f.content.instanceTransform[index(middle)];
  const bool materialEdit = state.range(0) != 0;
  double shadowTriangles = 0;
  float step = 0.2f;
  for (auto _ : state) {
    if (materialEdit) {
      Material m;
      m.baseColor = glm::vec3(0.8f, 0.3f, 0.2f);
      f.scene.setMaterial(MaterialId(0), m);
    } else {
      f.scene.setInstanceTransform(middle, glm::translate(at, glm::vec3(step, 0.0f, 0.0f)));
      step = -step;
    }
    renderer.render(f.scene, f.content.camera, Region::full(kWidth, kHeight), fb);
    shadowTriangles += double(renderer.lastStats().shadowTriangles);
  }
  f.scene.setInstanceTransform(middle, at);
  state.counters["shadowTriangles"] = benchmark::Counter(shadowTriangles, benchmark::Counter::kAvgIterations);
}

BENCHMARK(BM_FrameAfterAnEdit)
    ->ArgNames({"materialEdit"})
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

// Console output plus, at the end, each Tessera run's time relative to the minimal program.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs)
      if (r.run_type == Run::RT_Iteration) times_[r.benchmark_name()] = r.GetAdjustedRealTime();
  }
  void Finalize() override {
    ConsoleReporter::Finalize();
    auto base = times_.find("BM_MinimalVulkan/min_time:2.000/real_time");
    if (base == times_.end()) return;
    std::printf("\n%u x %u, %u instances; frame time relative to the minimal Vulkan program (target <= 1.3):\n", kWidth,
                kHeight, kInstances);
    for (const auto& [name, t] : times_) std::printf("  %-60s %8.1f ms  x%.2f\n", name.c_str(), t, t / base->second);
  }

 private:
  std::map<std::string, double> times_;
};

}  // namespace
}  // namespace tsr::vk::bench

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  tsr::vk::bench::RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
