// BM_Denoise/<method>: one denoise() of a 512x512 synthetic image (two
// coloured halves, a sky band, smooth light plus noise drawn per half of
// the samples) with the default settings, on all threads. The issue's
// budget is the time of tracing 4 spp of the same size (tessera-render
// builtin:cornell --size 512x512 --spp 4, docs/filtering.md).
#include "tsr/embree/denoiser.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {

using namespace tsr::embree;

struct Images {
  static constexpr std::uint32_t size = 512;
  std::vector<glm::vec3> colour, variance, albedo, normal, firstHalf;
  std::vector<float> depth, share;
  Images() {
    const std::size_t n = std::size_t(size) * size;
    colour.resize(n), variance.resize(n), albedo.resize(n), normal.resize(n), firstHalf.resize(n);
    depth.resize(n), share.assign(n, 0.5f);
    std::mt19937 rng(1);
    std::normal_distribution<float> noise(0.0f, 0.3f);
    for (std::uint32_t y = 0; y < size; ++y)
      for (std::uint32_t x = 0; x < size; ++x) {
        const std::size_t i = std::size_t(y) * size + x;
        const bool left = x < size / 2, sky = y < size / 3;
        albedo[i] = left ? glm::vec3(0.6f, 0.3f, 0.2f) : glm::vec3(0.2f, 0.4f, 0.7f);
        normal[i] = left ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1);
        depth[i] = sky ? std::numeric_limits<float>::infinity() : 2.0f + float(y) / size;
        const glm::vec3 light = albedo[i] * (1.0f + 0.5f * std::sin(float(x) / 30.0f));
        firstHalf[i] = light * (1.0f + noise(rng));
        colour[i] = 0.5f * (firstHalf[i] + light * (1.0f + noise(rng)));
        variance[i] = light * light * 0.045f;
      }
  }
  DenoiseInput input() const { return {size, size, colour, variance, albedo, normal, depth, firstHalf, share, {}}; }
};

void run(benchmark::State& state, DenoiseMethod method) {
  static const Images images;
  DenoiseSettings s;
  s.method = method;
  for (auto _ : state) benchmark::DoNotOptimize(denoise(images.input(), s));
  state.counters["Mpixel/s"] =
      benchmark::Counter(double(Images::size) * Images::size * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

BENCHMARK_CAPTURE(run, Regression, DenoiseMethod::Regression)
    ->Name("BM_Denoise/Regression")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(run, Atrous, DenoiseMethod::Atrous)
    ->Name("BM_Denoise/Atrous")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_MAIN();
