// Scene graph throughput: edits -> commit -> encode -> decode -> apply, in
// field changes per second, and the wire size of the smallest edits.
#include <benchmark/benchmark.h>

#include "tsr/sg/scene.hpp"
#include "tsr/sg/wire/wire_codec.hpp"

using namespace tsr::sg;

namespace {
Mat4 translation(float x) {
  Mat4 m(1.0f);
  m[3] = Vec4(x, 0, 0, 1);
  return m;
}

// A group of `n` transforms, each over one shared mesh, mirrored to a replica.
struct Mirrored {
  Scene source, replica;
  std::vector<Transform*> transforms;
  explicit Mirrored(int n) {
    auto& root = source.create<Group>();
    auto& mesh = source.create<Geometry>();
    mesh.setPositions({Vec3(0), Vec3(1, 0, 0), Vec3(0, 1, 0)});
    mesh.setIndices({0, 1, 2});
    for (int i = 0; i < n; ++i) {
      auto& t = source.create<Transform>();
      t.addChild(mesh.id());
      root.addChild(t.id());
      transforms.push_back(&t);
    }
    replica.apply(*decode(encode(*source.commit())));
  }
};
}  // namespace

// Arg: transforms edited per frame, in a scene of 10,000.
static void BM_CommitEncodeDecodeApply(benchmark::State& state) {
  Mirrored m(10000);
  const auto perFrame = static_cast<std::size_t>(state.range(0));
  std::uint64_t fields = 0, bytes = 0;
  float x = 0;
  for (auto _ : state) {
    x += 1;
    for (std::size_t i = 0; i < perFrame; ++i)
      m.transforms[(i * 7919) % m.transforms.size()]->setMatrix(translation(x));
    auto list = m.source.commit();
    auto wire = encode(*list);
    auto decoded = decode(wire);
    m.replica.apply(*decoded);
    fields += list->fieldChangeCount();
    bytes += wire.size();
  }
  if (m.replica.contentHash() != m.source.contentHash()) state.SkipWithError("replica diverged");
  state.SetItemsProcessed(static_cast<std::int64_t>(fields));
  state.counters["field_changes_per_s"] = benchmark::Counter(static_cast<double>(fields), benchmark::Counter::kIsRate);
  state.counters["bytes_per_field_change"] = static_cast<double>(bytes) / static_cast<double>(fields);
}
BENCHMARK(BM_CommitEncodeDecodeApply)->Arg(1)->Arg(100)->Arg(10000)->Unit(benchmark::kMicrosecond);

// Encoded size of a frame that changes one transform of a large scene.
static void BM_SingleTransformEditBytes(benchmark::State& state) {
  Mirrored m(10000);
  std::size_t size = 0;
  float x = 0;
  for (auto _ : state) {
    m.transforms[4321]->setMatrix(translation(x += 1));
    size = encode(*m.source.commit()).size();
    benchmark::DoNotOptimize(size);
  }
  state.counters["bytes_per_transform_edit"] = static_cast<double>(size);
}
BENCHMARK(BM_SingleTransformEditBytes);

// Snapshot of the 10,000-transform scene: the cost of a late join.
static void BM_SnapshotEncodeDecodeApply(benchmark::State& state) {
  Mirrored m(10000);
  std::size_t size = 0;
  for (auto _ : state) {
    auto wire = encode(*m.source.snapshot());
    size = wire.size();
    Scene late;
    late.apply(*decode(wire));
    benchmark::DoNotOptimize(late.size());
  }
  state.counters["snapshot_bytes"] = static_cast<double>(size);
}
BENCHMARK(BM_SnapshotEncodeDecodeApply)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
