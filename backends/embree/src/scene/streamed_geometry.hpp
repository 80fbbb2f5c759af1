#pragma once
// The merged level of a scene too large to hold whole. Below its budget
// (TraceMemory) the merged scene holds every single-use mesh copied to
// world space under one BVH. Above it, the merged scene holds clusters
// instead: instances grouped by where they stand, each cluster one Embree
// user primitive with the box around them. A cluster's world-space copy and
// BVH are made when a ray first reaches its box (the ray then traverses
// them), kept while they are used, and the least recently used are dropped
// once the built clusters pass the budget. The hits are the same triangles'
// hits as the merged scene's, so an image differs at most where a ray
// crosses a shared edge; how much of the scene is held depends only on
// where rays go. As in out-of-core ray tracers (Pharr et al. 1997, a
// geometry cache), memory is traded for builds: a view that reaches more
// clusters than the budget holds builds some of them again.

#include "scene/scene_state.hpp"

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

namespace tsr::embree {

// Estimated bytes of an instance's world-space copy and its share of a
// compact BVH (the 50M plant: 38 bytes a triangle in Embree's memory
// monitor), for the budget.
std::uint64_t mergedBytes(std::uint64_t vertices, std::uint64_t triangles);

class StreamedGeometry {
 public:
  StreamedGeometry(const SceneState& scene, TraceMemory budget);
  ~StreamedGeometry();
  StreamedGeometry(const StreamedGeometry&) = delete;
  StreamedGeometry& operator=(const StreamedGeometry&) = delete;

  // Groups the merged instances into clusters of about the budget's
  // triangles and attaches one user geometry for each to `merged` (ids
  // from 0), after detaching the last partition's; built clusters are
  // dropped. Called at commit, never while rays are traced.
  void partition(RTCScene merged);
  void detach(RTCScene merged);

  TraceMemoryUse use() const;
  const TraceMemory& budget() const { return budget_; }
  const SceneState& scene() const { return scene_; }

  struct Cluster;
  struct Built;
  // The cluster's world-space copy and BVH, built if it has none; holding
  // the pointer keeps it from being dropped. Thread-safe.
  std::shared_ptr<const Built> acquire(Cluster& c);

 private:
  std::shared_ptr<Built> make(const Cluster& c) const;
  bool commit(const std::shared_ptr<Built>& made) const;  // false when Embree could not build it
  static void fail(Cluster& c, const char* why);
  // Drops the least recently used built clusters but `keep` until the held
  // ones fit the budget (under cache_); returns them to be released after
  // the locks (a tracer's copy keeps one alive until its ray is done).
  std::vector<std::shared_ptr<const Built>> evictOver(const Cluster& keep);

  const SceneState& scene_;
  const TraceMemory budget_;
  const bool parallelCommit_;  // threads may commit one scene together (Embree with TBB)
  std::vector<std::unique_ptr<Cluster>> clusters_;
  std::vector<RTCGeometry> geometries_;  // one user geometry a cluster, attached at its index
  mutable std::mutex cache_;             // guards the figures below and which clusters are built
  std::uint64_t heldBytes_ = 0;
  std::atomic<std::uint64_t> clock_{0};  // counts rays reaching built clusters: orders their last use
  std::uint64_t builds_ = 0, evictions_ = 0;
};

}  // namespace tsr::embree
