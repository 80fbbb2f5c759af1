// Path tracer rays/s against raw incoherent rtcIntersect1 rays/s on the same
// scene in the same run: the Cornell box of tests/bench/scenes/make_cornell.py
// with its ~1M-triangle sphere. Prints the ratio at the end.
#include "rays_per_second.hpp"
#include "test_scenes.hpp"
#include "tsr/embree/rng.hpp"

#include <benchmark/benchmark.h>
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <string>
#include <thread>

namespace {

using namespace tsr::embree;

struct Bench {
  Scene scene{test::sharedDevice()};
  Camera camera;
  Bench() {
    camera = test::cornellBox(scene, 1000000);
    scene.commit();
    // TBB workers keep spinning for a while after the BVH build (an idle TBB arena spins before it sleeps).
    std::this_thread::sleep_for(std::chrono::seconds(2));
  }
};

Bench& bench() {
  static Bench b;
  return b;
}

int threads() { return tbb::info::default_concurrency(); }

void BM_PathTracer(benchmark::State& state) {
  Bench& b = bench();
  RenderSettings s;
  s.maxDepth = 8;
  s.threads = threads();
  Renderer renderer(s);
  const std::uint32_t size = 256;
  FrameBuffer fb(size, size);
  std::uint64_t rays = 0;
  for (auto _ : state) rays += renderer.renderPass(b.scene, b.camera, Region::full(size, size), fb).rays;
  state.counters["rays/s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
  state.counters["threads"] = threads();
}

void BM_RawIntersect1(benchmark::State& state) {
  Bench& b = bench();
  // Incoherent rays: uniform origins inside the box, uniform directions.
  const std::size_t n = 1 << 20;
  std::vector<RTCRayHit> rays(n);
  for (std::size_t i = 0; i < n; ++i) {
    Rng rng(Rng::pixelKey(1, std::uint32_t(i), 0), 0);
    glm::vec3 o(5.0f + 540.0f * rng.uniform(), 5.0f + 540.0f * rng.uniform(), 5.0f + 550.0f * rng.uniform());
    glm::vec3 d = sampleUniformSphere(rng.uniform2());
    RTCRayHit& r = rays[i];
    r.ray = {o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, 0.0f, std::numeric_limits<float>::infinity(), ~0u, 0, 0};
    r.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    r.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  }
  RTCScene scene = b.scene.embreeScene();
  tbb::task_arena arena(threads());
  std::uint64_t count = 0, hits = 0;
  for (auto _ : state) {
    std::atomic<std::uint64_t> hitCount{0};
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        std::uint64_t h = 0;
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          // Copied whole, ready to trace: patching tfar into the copy would
          // make Embree's 16-byte load of it wait (no store forwarding).
          RTCRayHit rh = rays[i];
          rtcIntersect1(scene, &ctx, &rh);
          h += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        }
        hitCount += h;
      });
    });
    count += n;
    hits += hitCount.load();
  }
  state.counters["rays/s"] = benchmark::Counter(double(count), benchmark::Counter::kIsRate);
  state.counters["hit%"] = count ? 100.0 * double(hits) / double(count) : 0.0;
  state.counters["threads"] = threads();
}

BENCHMARK(BM_RawIntersect1)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
BENCHMARK(BM_PathTracer)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  tsr::bench::RaysPerSecond reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  const double pt = reporter.of("BM_PathTracer"), raw = reporter.of("BM_RawIntersect1");
  if (pt > 0.0 && raw > 0.0) {
    std::printf("path tracer %.2f Mrays/s, raw rtcIntersect1 %.2f Mrays/s, ratio %.1f %%\n", pt * 1e-6, raw * 1e-6,
                100.0 * pt / raw);
  }
  benchmark::Shutdown();
  return 0;
}
