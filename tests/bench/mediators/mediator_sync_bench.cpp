// What one edit costs a converted Embree scene of builtin:instances:N,
// against converting that scene from scratch: end to end through a render
// of one pixel with one sample (which adds Embree's acceleration structure
// builds; Embree 3 cannot refit instance levels, so an instance that moves
// goes to a small level of the instances that moved, leaving a ghost in the
// top level over all N, which rebuilds once per 2 sqrt(N) such first moves),
// and the mediator's part alone (Viewport::synchronize). The
// edits are one moved transform (the same one, or a different one each time),
// one material's colour and a two-vertex range of one geometry (its mesh, used
// by every instance, keeps its bounds, so no instance moves); run all with
// --benchmark_filter='/(10000|100000)$'. Their mediator cost must not grow
// with N.
#include <map>
#include <memory>

#include <benchmark/benchmark.h>

#include <glm/gtc/matrix_transform.hpp>

#include "../instances_fixture.hpp"
#include "tsr/med/embree/register.hpp"

using namespace tsr;

namespace {
using Instances = bench::InstancesFixture;

Instances& scene(std::int64_t count) {
  static std::map<std::int64_t, std::unique_ptr<Instances>> scenes;
  auto& s = scenes[count];
  if (!s) {
    med::Parameters p;
    p.set("spp", std::int64_t{1});
    s = std::make_unique<Instances>("embree", med::registerEmbree, p, count);
  }
  return *s;
}

// One edit of the source scene, the i-th of the run.
using Edit = void (*)(Instances&, int i);

// Edits are numbered over the whole program, so none sets the value an
// earlier one left (which changes nothing): Google Benchmark runs each
// function several times, to pick its iteration count and to repeat.
int nextEdit() {
  static int n = 0;
  return ++n;
}

void moveOneTransform(Instances& s, int i) {
  s.transforms[s.transforms.size() / 2]->setMatrix(glm::translate(glm::mat4(1.0f), glm::vec3(0.01f * i, 0, 0)));
}
// A different instance each time: the first move of an instance ghosts it in
// the top level, and every 2 sqrt(N)-th folds the ghosts back (a rebuild of the
// top level); between folds only the moving level rebuilds.
void moveAnotherTransform(Instances& s, int i) {
  s.transforms[std::size_t(i) % s.transforms.size()]->setMatrix(
      glm::translate(glm::mat4(1.0f), glm::vec3(0, 0.01f * i, 0)));
}
// A millimetre, to an instance spread over the grid: the frame stays the same.
void nudgeAnotherTransform(Instances& s, int i) {
  sg::Transform& t = *s.transforms[std::size_t(i) * 7919 % s.transforms.size()];
  t.setMatrix(glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 1e-3f)) * t.matrix());
}
void tintOneMaterial(Instances& s, int i) {
  s.materials.front()->setBaseColor(glm::vec3(0.5f, 0.5f, (i % 100) / 100.0f));
}
void nudgeTwoVertices(Instances& s, int i) {
  sg::Geometry& g = *s.geometries.front();
  std::vector<sg::Vec3> run(g.positions().begin(), g.positions().begin() + 2);
  for (auto& p : run) p.y += (i % 2 ? 1e-3f : -1e-3f);
  g.updatePositions(0, run);
}

// A replica of builtin:instances:N with a viewport that has converted it.
struct Converted {
  explicit Converted(Instances& s) : replica(4) {
    replica.apply(s.source.snapshot());
    viewport = s.registry.create(s.settings(), contexts);
    viewport->render(replica, s.onePixel(replica.scene()), out);
  }
  sg::Replica replica;
  med::ContextPool contexts;
  std::unique_ptr<med::Viewport> viewport;
  med::FrameBuffer out;
};

// A converted viewport; each iteration edits, ships the change list (not
// timed: the scene graph's cost, measured elsewhere) and brings the viewport
// up to date, end to end or the mediator's part only.
void syncAfterEdit(benchmark::State& state, Edit edit, bool endToEnd) {
  Instances& s = scene(state.range(0));
  Converted c(s);
  auto& [replica, contexts, viewport, out] = c;
  for (auto _ : state) {
    state.PauseTiming();
    edit(s, nextEdit());
    replica.apply(s.source.commit());
    state.ResumeTiming();
    auto update =
        endToEnd ? viewport->render(replica, s.onePixel(replica.scene()), out).update : viewport->synchronize(replica);
    if (update != med::SceneAdapter::Update::Synced) state.SkipWithError("expected a sync");
  }
  state.counters["instances"] = static_cast<double>(state.range(0));
}

void sizes(benchmark::internal::Benchmark* b) { b->Arg(10000)->Arg(100000); }
}  // namespace

static void BM_ConvertInstances(benchmark::State& state) {
  Instances& s = scene(state.range(0));
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
BENCHMARK(BM_ConvertInstances)->Apply(sizes)->Unit(benchmark::kMillisecond);

static void BM_MediatorConvertOnly(benchmark::State& state) {
  Instances& s = scene(state.range(0));
  sg::Replica replica;
  replica.apply(s.source.snapshot());
  for (auto _ : state) {
    med::ContextPool contexts;
    auto viewport = s.registry.create(s.settings(), contexts);
    if (viewport->synchronize(replica) != med::SceneAdapter::Update::Converted)
      state.SkipWithError("expected a conversion");
  }
}
BENCHMARK(BM_MediatorConvertOnly)->Apply(sizes)->Unit(benchmark::kMillisecond);

static void BM_SyncOneTransformEdit(benchmark::State& state) { syncAfterEdit(state, moveOneTransform, true); }
static void BM_SyncFirstTransformEdit(benchmark::State& state) { syncAfterEdit(state, moveAnotherTransform, true); }
static void BM_SyncMaterialEdit(benchmark::State& state) { syncAfterEdit(state, tintOneMaterial, true); }
static void BM_SyncPointsRangeEdit(benchmark::State& state) { syncAfterEdit(state, nudgeTwoVertices, true); }
static void BM_MediatorSyncOnlyOneTransformEdit(benchmark::State& state) {
  syncAfterEdit(state, moveOneTransform, false);
}
static void BM_MediatorSyncOnlyMaterialEdit(benchmark::State& state) { syncAfterEdit(state, tintOneMaterial, false); }
static void BM_MediatorSyncOnlyPointsRangeEdit(benchmark::State& state) {
  syncAfterEdit(state, nudgeTwoVertices, false);
}
// What ghosts cost a frame: one sample per pixel of a 64x64 view after
// `moved` different instances moved (a millimetre) once each (their ghosts stay in the top
// level until 2 sqrt(N) of them), against the same frame with none moved.
static void BM_RenderAfterMoves(benchmark::State& state) {
  Instances& s = scene(state.range(0));
  Converted c(s);
  auto& [replica, contexts, viewport, out] = c;
  for (int i = 0; i < state.range(1); ++i) {
    nudgeAnotherTransform(s, nextEdit());
    replica.apply(s.source.commit());
    viewport->render(replica, s.onePixel(replica.scene()), out);
  }
  // Two poses a hair apart, so each frame restarts accumulation and traces all its pixels.
  med::View frames[2] = {s.view(replica.scene(), 64, 64), s.view(replica.scene(), 64, 64)};
  frames[1].cameraToWorld[3].x += 1e-4f;
  int i = 0;
  for (auto _ : state) viewport->render(replica, frames[++i % 2], out);
}
BENCHMARK(BM_RenderAfterMoves)->Args({10000, 0})->Args({10000, 199})->Unit(benchmark::kMillisecond);

BENCHMARK(BM_SyncOneTransformEdit)->Apply(sizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SyncFirstTransformEdit)->Apply(sizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SyncMaterialEdit)->Apply(sizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SyncPointsRangeEdit)->Apply(sizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MediatorSyncOnlyOneTransformEdit)->Apply(sizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MediatorSyncOnlyMaterialEdit)->Apply(sizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MediatorSyncOnlyPointsRangeEdit)->Apply(sizes)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
