// What the history (temporal reprojection) costs a frame: the Cornell box
// of make_cornell.py at 500x400, the camera turning 2 degrees a frame, one
// sample per pixel a frame; the pass with a restart, the pass with a
// reprojection, and the reprojection alone. Prints the reprojection's share
// of a frame at the end (issue 43's target: under 10 %).
#include "test_scenes.hpp"

#include <benchmark/benchmark.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cstdio>
#include <map>
#include <string>

namespace {

using namespace tsr::embree;

constexpr std::uint32_t kWidth = 500, kHeight = 400;

struct Bench {
  Scene scene{test::sharedDevice()};
  Camera camera;
  Bench() {
    camera = test::cornellBox(scene, 0, float(kWidth) / float(kHeight));
    scene.commit();
  }
  // The camera turned about the box's centre by `degrees`.
  Camera turned(float degrees) const {
    Camera c = camera;
    const glm::vec3 pivot(278.0f, 274.0f, 280.0f);
    c.cameraToWorld = glm::translate(glm::mat4(1.0f), pivot) *
                      glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::vec3(0, 1, 0)) *
                      glm::translate(glm::mat4(1.0f), -pivot) * camera.cameraToWorld;
    return c;
  }
};

Bench& bench() {
  static Bench b;
  return b;
}

std::map<std::string, double> seconds;

// One frame: the camera turns, then (unless only reprojecting) one pass.
void frames(benchmark::State& state, std::uint32_t historyLimit, bool pass) {
  Bench& b = bench();
  RenderSettings s;
  s.historyLimit = historyLimit;
  Renderer renderer(s);
  const Region region = Region::full(kWidth, kHeight);
  FrameBuffer fb(kWidth, kHeight);
  for (int warm = 0; warm < 8; ++warm) renderer.renderPass(b.scene, b.turned(2.0f * float(warm)), region, fb);
  int frame = 8;
  for (auto _ : state) {
    const Camera c = b.turned(2.0f * float(frame++ % 30));
    if (pass) {
      renderer.renderPass(b.scene, c, region, fb);
    } else {
      renderer.restartIfStale(b.scene, c, region, fb);
    }
    benchmark::DoNotOptimize(fb.sampleCount(0, 0));
  }
}

void BM_FrameRestarting(benchmark::State& state) { frames(state, 0, true); }
void BM_FrameWithHistory(benchmark::State& state) { frames(state, 16, true); }
void BM_ReprojectionAlone(benchmark::State& state) { frames(state, 16, false); }

BENCHMARK(BM_FrameRestarting)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_FrameWithHistory)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_ReprojectionAlone)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

// Keeps each benchmark's real time per iteration for the closing line.
class Recorder : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const auto& r : runs) seconds[r.benchmark_name()] = r.GetAdjustedRealTime();
  }
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  Recorder recorder;
  benchmark::RunSpecifiedBenchmarks(&recorder);
  const double restart = seconds["BM_FrameRestarting/min_time:2.000/real_time"];
  const double history = seconds["BM_FrameWithHistory/min_time:2.000/real_time"];
  const double alone = seconds["BM_ReprojectionAlone/min_time:2.000/real_time"];
  if (restart > 0 && history > 0)
    std::printf("reprojection: %.1f ms alone, %.1f %% of a restarting frame; a frame with history takes %.2fx "
                "one restarting\n",
                alone, 100.0 * alone / restart, history / restart);
  benchmark::Shutdown();
  return 0;
}
