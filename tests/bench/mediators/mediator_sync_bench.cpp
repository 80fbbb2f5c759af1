// What a one-transform edit costs a converted Embree scene of
// builtin:instances:10000, against converting that scene from scratch,
// twice: the mediator's part alone (Viewport::synchronize), and end to end
// through a render of one pixel with one sample, which adds Embree's
// acceleration structure builds (for an edit, the top level over 10,000
// instances: Embree 3 cannot refit instance levels).
#include <benchmark/benchmark.h>

#include <glm/gtc/matrix_transform.hpp>

#include "tsr/med/embree/register.hpp"
#include "../instances_fixture.hpp"

using namespace tsr;

namespace {
using Instances = bench::InstancesFixture;
Instances& scene() {
  static Instances instances("embree", med::registerEmbree, [] {
    med::Parameters p;
    p.set("spp", std::int64_t{1});
    return p;
  }());
  return instances;
}
}  // namespace

static void BM_ConvertInstances10000(benchmark::State& state) {
  Instances& s = scene();
  sg::Replica replica;
  replica.apply(s.source.snapshot());
  med::FrameBuffer out;
  for (auto _ : state) {
    med::ContextPool contexts;  // a new context: conversion from nothing
    auto viewport = s.registry.create(s.settings(), contexts);
    auto stats = viewport->render(replica, s.onePixel(replica.scene()), out);
    if (stats.update != med::SceneAdapter::Update::Converted) state.SkipWithError("expected a conversion");
  }
}
BENCHMARK(BM_ConvertInstances10000)->Unit(benchmark::kMillisecond)->MinTime(2.0);

static void BM_SyncOneTransformEdit(benchmark::State& state) {
  Instances& s = scene();
  sg::Replica replica(4);
  replica.apply(s.source.snapshot());
  med::ContextPool contexts;
  auto viewport = s.registry.create(s.settings(), contexts);
  med::FrameBuffer out;
  viewport->render(replica, s.onePixel(replica.scene()), out);
  float x = 0;
  for (auto _ : state) {
    state.PauseTiming();  // the edit and its transport are the scene graph's cost, measured elsewhere
    s.transforms[1234]->setMatrix(glm::translate(glm::mat4(1.0f), glm::vec3(x += 0.01f, 0, 0)));
    replica.apply(s.source.commit());
    state.ResumeTiming();
    auto stats = viewport->render(replica, s.onePixel(replica.scene()), out);
    if (stats.update != med::SceneAdapter::Update::Synced) state.SkipWithError("expected a sync");
  }
}
BENCHMARK(BM_SyncOneTransformEdit)->Unit(benchmark::kMicrosecond)->MinTime(2.0);

static void BM_MediatorConvertOnly(benchmark::State& state) {
  Instances& s = scene();
  sg::Replica replica;
  replica.apply(s.source.snapshot());
  for (auto _ : state) {
    med::ContextPool contexts;
    auto viewport = s.registry.create(s.settings(), contexts);
    if (viewport->synchronize(replica) != med::SceneAdapter::Update::Converted) state.SkipWithError("expected a conversion");
  }
}
BENCHMARK(BM_MediatorConvertOnly)->Unit(benchmark::kMillisecond)->MinTime(2.0);

static void BM_MediatorSyncOnlyOneTransformEdit(benchmark::State& state) {
  Instances& s = scene();
  sg::Replica replica(4);
  replica.apply(s.source.snapshot());
  med::ContextPool contexts;
  auto viewport = s.registry.create(s.settings(), contexts);
  viewport->synchronize(replica);
  float x = 0;
  for (auto _ : state) {
    state.PauseTiming();
    s.transforms[4321]->setMatrix(glm::translate(glm::mat4(1.0f), glm::vec3(x += 0.01f, 0, 0)));
    replica.apply(s.source.commit());
    state.ResumeTiming();
    if (viewport->synchronize(replica) != med::SceneAdapter::Update::Synced) state.SkipWithError("expected a sync");
  }
}
BENCHMARK(BM_MediatorSyncOnlyOneTransformEdit)->Unit(benchmark::kMicrosecond)->MinTime(2.0);

BENCHMARK_MAIN();
