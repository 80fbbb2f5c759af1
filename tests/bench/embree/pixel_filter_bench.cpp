// BM_PixelFilter/<kernel>: filterHighVariance on a 512x512 synthetic image
// (smooth radiance plus noise, range buffer with colour and depth edges),
// sigmaS = 8, on all threads.
#include "tsr/embree/pixel_filter.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {

using namespace tsr::embree;

struct Images {
  static constexpr std::uint32_t size = 512;
  std::vector<glm::vec3> lu, var, llv, colour;
  std::vector<float> depth;
  Images() {
    const std::size_t n = std::size_t(size) * size;
    lu.resize(n), var.resize(n), llv.resize(n), colour.resize(n), depth.resize(n);
    std::mt19937 rng(1);
    std::normal_distribution<float> noise(0.0f, 0.2f);
    for (std::uint32_t y = 0; y < size; ++y)
      for (std::uint32_t x = 0; x < size; ++x) {
        const std::size_t i = std::size_t(y) * size + x;
        const bool left = x < size / 2, top = y < size / 3;
        colour[i] = left ? glm::vec3(0.6f, 0.3f, 0.2f) : glm::vec3(0.2f, 0.4f, 0.7f);
        depth[i] = top ? std::numeric_limits<float>::infinity() : 2.0f + float(y) / size;
        lu[i] = glm::vec3(1.0f + 0.5f * std::sin(float(x) / 30.0f) + noise(rng));
        var[i] = glm::vec3(0.04f);
        llv[i] = glm::vec3(0.5f);
      }
  }
  PixelFilterInput input() const { return {size, size, lu, var, llv, colour, depth, 4, {}}; }
};

void run(benchmark::State& state, FilterKernel kernel, bool extras) {
  static const Images images;
  PixelFilterSettings s;
  s.kernel = kernel;
  s.adaptiveWidth = s.antialiasRecovery = extras;
  for (auto _ : state) benchmark::DoNotOptimize(filterHighVariance(images.input(), s));
  state.counters["Mpixel/s"] =
      benchmark::Counter(double(Images::size) * Images::size * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
}

void BM_PixelFilterBlend(benchmark::State& state) {
  static const Images images;
  PixelFilterSettings s;
  s.kernel = FilterKernel::Atrous;
  const FilteredBuffer fb = filterHighVariance(images.input(), s);
  for (auto _ : state) benchmark::DoNotOptimize(blend(images.input(), fb, s));
}

}  // namespace

BENCHMARK_CAPTURE(run, Bilateral, FilterKernel::Bilateral, false)
    ->Name("BM_PixelFilter/Bilateral")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(run, Separable, FilterKernel::Separable, false)
    ->Name("BM_PixelFilter/Separable")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(run, Atrous, FilterKernel::Atrous, false)
    ->Name("BM_PixelFilter/Atrous")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(run, SeparableAdaptiveAA, FilterKernel::Separable, true)
    ->Name("BM_PixelFilter/SeparableAdaptiveAA")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_PixelFilterBlend)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
