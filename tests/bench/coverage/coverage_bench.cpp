// The coverage back-end through its mediator on builtin:instances:10000:
// a full-HD id pass (pixels/s), the same plus the ranking a culling service
// sends, converting the scene from nothing, and one moved transform
// (which rebuilds Embree's top level over 10,000 instances).
#include <benchmark/benchmark.h>

#include <glm/gtc/matrix_transform.hpp>

#include "../instances_fixture.hpp"
#include "tsr/med/coverage/ranking.hpp"
#include "tsr/med/coverage/register.hpp"

using namespace tsr;

namespace {
using Instances = bench::InstancesFixture;
Instances& scene() {
  static Instances instances("coverage", med::registerCoverage);
  return instances;
}

// A converted viewport on its own replica.
struct Converted {
  sg::Replica replica{4};
  med::ContextPool contexts;
  std::unique_ptr<med::Viewport> viewport;
  explicit Converted(Instances& s) {
    replica.apply(s.source.snapshot());
    viewport = s.registry.create(s.settings(), contexts);
    viewport->synchronize(replica);
  }
};
}  // namespace

static void BM_IdPass1080p(benchmark::State& state) {
  Instances& s = scene();
  Converted c(s);
  const med::View view = s.view(c.replica.scene(), 1920, 1080);
  med::FrameBuffer out;
  c.viewport->render(c.replica, view, out);  // commits the acceleration structures
  for (auto _ : state) c.viewport->render(c.replica, view, out);
  state.counters["pixels_per_second"] =
      benchmark::Counter(double(state.iterations()) * 1920 * 1080, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_IdPass1080p)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

static void BM_IdPassAndRanking1080p(benchmark::State& state) {
  Instances& s = scene();
  Converted c(s);
  const med::View view = s.view(c.replica.scene(), 1920, 1080);
  med::FrameBuffer out;
  c.viewport->render(c.replica, view, out);
  std::size_t visible = 0;
  for (auto _ : state) {
    c.viewport->render(c.replica, view, out);
    visible = med::rankObjects(out, c.replica.scene()).size();
  }
  state.counters["visible_objects"] = double(visible);
  state.counters["pixels_per_second"] =
      benchmark::Counter(double(state.iterations()) * 1920 * 1080, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_IdPassAndRanking1080p)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

static void BM_ConvertInstances10000(benchmark::State& state) {
  Instances& s = scene();
  sg::Replica replica;
  replica.apply(s.source.snapshot());
  const med::View pixel = s.onePixel(replica.scene());
  med::FrameBuffer out;
  for (auto _ : state) {
    med::ContextPool contexts;  // a new context: conversion from nothing
    auto viewport = s.registry.create(s.settings(), contexts);
    if (viewport->render(replica, pixel, out).update != med::SceneAdapter::Update::Converted)
      state.SkipWithError("expected a conversion");
  }
}
BENCHMARK(BM_ConvertInstances10000)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

static void BM_SyncOneTransformEdit(benchmark::State& state) {
  Instances& s = scene();
  Converted c(s);
  const med::View pixel = s.onePixel(c.replica.scene());
  med::FrameBuffer out;
  c.viewport->render(c.replica, pixel, out);
  float x = 0;
  for (auto _ : state) {
    state.PauseTiming();  // the edit and its transport are the scene graph's cost, measured elsewhere
    s.transforms[1234]->setMatrix(glm::translate(glm::mat4(1.0f), glm::vec3(x += 0.01f, 0, 0)));
    c.replica.apply(s.source.commit());
    state.ResumeTiming();
    if (c.viewport->render(c.replica, pixel, out).update != med::SceneAdapter::Update::Synced)
      state.SkipWithError("expected a sync");
  }
}
BENCHMARK(BM_SyncOneTransformEdit)->Unit(benchmark::kMicrosecond)->UseRealTime()->MinTime(2.0);

BENCHMARK_MAIN();
