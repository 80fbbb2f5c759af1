#include "scene/streamed_geometry.hpp"

#include "scene/scene_levels.hpp"
#include "tracing/alpha_test.hpp"
#include "tsr/embree/error.hpp"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>

namespace tsr::embree {

namespace {

// A container's memory limit (cgroup v2's memory.max), when one is set.
std::optional<std::uint64_t> cgroupLimit() {
  std::ifstream in("/sys/fs/cgroup/memory.max");
  std::uint64_t bytes = 0;
  if (in >> bytes) return bytes;  // "max" (no limit) does not parse
  return std::nullopt;
}

}  // namespace

std::uint64_t TraceMemory::defaultBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
  std::uint64_t machine = pages > 0 && size > 0 ? std::uint64_t(pages) * std::uint64_t(size) : std::uint64_t(24) << 30;
  if (const auto limit = cgroupLimit()) machine = std::min(machine, *limit);
  return std::max<std::uint64_t>(machine / 6, 1);
}

std::uint64_t mergedBytes(std::uint64_t vertices, std::uint64_t triangles) {
  constexpr std::uint64_t kGeometryBytes = 512;  // Embree's geometry object and buffer headers
  return sizeof(glm::vec3) * vertices + 38 * triangles + kGeometryBytes;
}

struct StreamedGeometry::Built {
  RTCScene scene = nullptr;
  std::uint64_t bytes = 0;
  Built() = default;
  Built(const Built&) = delete;
  Built& operator=(const Built&) = delete;
  ~Built() {
    if (scene) rtcReleaseScene(scene);
  }
};

struct StreamedGeometry::Cluster {
  StreamedGeometry* owner = nullptr;
  std::vector<std::uint32_t> instances;  // geometry id in the built scene -> instance id
  RTCBounds bounds{};
  std::uint64_t bytes = 0;         // estimated, mergedBytes
  std::mutex building;             // one thread makes the copies; every thread that needs them joins the commit
  std::shared_ptr<Built> pending;  // made and maybe being committed (under `building`)
  // Committed and held: read by every ray that reaches the box, set under
  // `building` and the owner's cache_. A tracer's copy keeps it alive when
  // it is dropped meanwhile.
  std::atomic<std::shared_ptr<const Built>> built;
  std::atomic<std::uint64_t> lastUse{0};  // the owner's clock when a ray last reached it
  bool failed = false;  // Embree could not build it (under `building`): traced as empty until the next partition
};

namespace {

using Cluster = StreamedGeometry::Cluster;

// The context of a ray inside a cluster: alpha-tested hits are decided as
// the top level's filter decides them in the merged scene (geometry ids
// here are the cluster's, renamed to instances).
struct ClusterContext {
  RTCIntersectContext context;  // first: Embree hands the filter a pointer to it
  const SceneState* scene;
  const std::vector<std::uint32_t>* instances;

  ClusterContext(const SceneState& s, const Cluster& c, const RTCIntersectContext& outer)
      : scene(&s), instances(&c.instances) {
    rtcInitIntersectContext(&context);
    context.flags = outer.flags;
    if (s.alphaTested) [[unlikely]]
      context.filter = filter;
  }

  static void filter(const RTCFilterFunctionNArguments* args) {
    const auto& self = *reinterpret_cast<const ClusterContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
      if (args->valid[i] == 0) continue;
      const std::uint32_t geom = RTCHitN_geomID(args->hit, args->N, i);
      const std::uint32_t inst = geom < self.instances->size() ? (*self.instances)[geom] : kNoId;
      if (alphaRejects(*self.scene, inst, args, i)) args->valid[i] = 0;
    }
  }
};
static_assert(std::is_standard_layout_v<ClusterContext>);

RTCRay rayOf(RTCRayN* rays, unsigned n, unsigned i) {
  RTCRay r;
  r.org_x = RTCRayN_org_x(rays, n, i), r.org_y = RTCRayN_org_y(rays, n, i), r.org_z = RTCRayN_org_z(rays, n, i);
  r.tnear = RTCRayN_tnear(rays, n, i);
  r.dir_x = RTCRayN_dir_x(rays, n, i), r.dir_y = RTCRayN_dir_y(rays, n, i), r.dir_z = RTCRayN_dir_z(rays, n, i);
  r.time = RTCRayN_time(rays, n, i);
  r.tfar = RTCRayN_tfar(rays, n, i);
  r.mask = RTCRayN_mask(rays, n, i), r.id = RTCRayN_id(rays, n, i), r.flags = RTCRayN_flags(rays, n, i);
  return r;
}

void boundsOf(const RTCBoundsFunctionArguments* args) {
  *args->bounds_o = static_cast<const Cluster*>(args->geometryUserPtr)->bounds;
}

void intersectCluster(const RTCIntersectFunctionNArguments* args) {
  auto& c = *static_cast<Cluster*>(args->geometryUserPtr);
  const auto built = c.owner->acquire(c);
  if (!built) return;
  ClusterContext context(c.owner->scene(), c, *args->context);
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    RTCRayHit rh;
    rh.ray = rayOf(rays, args->N, i);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(built->scene, &context.context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
    RTCRayN_tfar(rays, args->N, i) = rh.ray.tfar;
    RTCHitN_Ng_x(hits, args->N, i) = rh.hit.Ng_x;
    RTCHitN_Ng_y(hits, args->N, i) = rh.hit.Ng_y;
    RTCHitN_Ng_z(hits, args->N, i) = rh.hit.Ng_z;
    RTCHitN_u(hits, args->N, i) = rh.hit.u;
    RTCHitN_v(hits, args->N, i) = rh.hit.v;
    RTCHitN_primID(hits, args->N, i) = rh.hit.primID;
    // In the merged scene a hit names its instance by geometry id.
    RTCHitN_geomID(hits, args->N, i) = c.instances[rh.hit.geomID];
    for (unsigned l = 0; l < RTC_MAX_INSTANCE_LEVEL_COUNT; ++l)
      RTCHitN_instID(hits, args->N, i, l) = args->context->instID[l];
  }
}

void occludedCluster(const RTCOccludedFunctionNArguments* args) {
  auto& c = *static_cast<Cluster*>(args->geometryUserPtr);
  const auto built = c.owner->acquire(c);
  if (!built) return;
  ClusterContext context(c.owner->scene(), c, *args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    RTCRay ray = rayOf(args->ray, args->N, i);
    rtcOccluded1(built->scene, &context.context, &ray);
    if (ray.tfar < 0.0f) RTCRayN_tfar(args->ray, args->N, i) = -std::numeric_limits<float>::infinity();
  }
}

RTCBounds emptyBounds() {
  const float inf = std::numeric_limits<float>::infinity();
  RTCBounds b{};
  b.lower_x = b.lower_y = b.lower_z = inf;
  b.upper_x = b.upper_y = b.upper_z = -inf;
  return b;
}

void grow(RTCBounds& b, const glm::vec3& p) {
  b.lower_x = std::min(b.lower_x, p.x), b.lower_y = std::min(b.lower_y, p.y), b.lower_z = std::min(b.lower_z, p.z);
  b.upper_x = std::max(b.upper_x, p.x), b.upper_y = std::max(b.upper_y, p.y), b.upper_z = std::max(b.upper_z, p.z);
}

// The box around an instance's vertices in world space, transformed as
// worldGeometry transforms them (so it is the box Embree would make).
RTCBounds worldBounds(const MeshData& d, const glm::mat4& transform) {
  RTCBounds b = emptyBounds();
  for (const glm::vec3& p : d.positions) grow(b, glm::vec3(transform * glm::vec4(p, 1.0f)));
  return b;
}

// 21 bits of each coordinate, interleaved: nearby points get nearby codes.
std::uint64_t spread(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffull;
  x = (x | x << 16) & 0x1f0000ff0000ffull;
  x = (x | x << 8) & 0x100f00f00f00f00full;
  x = (x | x << 4) & 0x10c30c30c30c30c3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

}  // namespace

StreamedGeometry::StreamedGeometry(const SceneState& scene, TraceMemory budget)
    : scene_(scene),
      budget_(budget),
      parallelCommit_(rtcGetDeviceProperty(scene.device->handle(), RTC_DEVICE_PROPERTY_PARALLEL_COMMIT_SUPPORTED) !=
                      0) {}

StreamedGeometry::~StreamedGeometry() {
  for (RTCGeometry g : geometries_) rtcReleaseGeometry(g);
}

void StreamedGeometry::detach(RTCScene merged) {
  for (std::uint32_t k = 0; k < geometries_.size(); ++k) {
    rtcDetachGeometry(merged, k);
    rtcReleaseGeometry(geometries_[k]);
  }
  geometries_.clear();
  clusters_.clear();
  heldBytes_ = 0;
}

void StreamedGeometry::partition(RTCScene merged) {
  detach(merged);
  struct Entry {
    std::uint64_t code;
    std::uint32_t instance;
    RTCBounds bounds;
    glm::vec3 centre;
  };
  std::vector<Entry> entries;
  RTCBounds centres = emptyBounds();
  for (std::uint32_t id = 0; id < scene_.instances.size(); ++id) {
    const auto& inst = scene_.instances[id];
    if (!inst || inst->level != Level::Merged) continue;
    const RTCBounds b = worldBounds(scene_.meshes[index(inst->mesh)]->data, inst->transform);
    entries.push_back(
        {0, id, b, 0.5f * glm::vec3(b.lower_x + b.upper_x, b.lower_y + b.upper_y, b.lower_z + b.upper_z)});
    grow(centres, entries.back().centre);
  }
  const glm::vec3 lo(centres.lower_x, centres.lower_y, centres.lower_z);
  const glm::vec3 extent =
      glm::max(glm::vec3(centres.upper_x, centres.upper_y, centres.upper_z) - lo, glm::vec3(1e-30f));
  for (Entry& e : entries) {
    const glm::vec3 q = glm::clamp((e.centre - lo) / extent, 0.0f, 1.0f) * float(0x1fffff);
    e.code = spread(std::uint64_t(q.x)) | spread(std::uint64_t(q.y)) << 1 | spread(std::uint64_t(q.z)) << 2;
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.code != b.code ? a.code < b.code : a.instance < b.instance;
  });
  std::uint64_t triangles = 0;
  for (const Entry& e : entries) {
    if (clusters_.empty() || triangles >= budget_.clusterTriangles) {
      clusters_.push_back(std::make_unique<Cluster>());
      clusters_.back()->owner = this;
      clusters_.back()->bounds = emptyBounds();
      triangles = 0;
    }
    Cluster& c = *clusters_.back();
    const MeshData& d = scene_.meshes[index(scene_.instances[e.instance]->mesh)]->data;
    c.instances.push_back(e.instance);
    c.bytes += mergedBytes(d.positions.size(), d.indices.size() / 3);
    triangles += d.indices.size() / 3;
    grow(c.bounds, {e.bounds.lower_x, e.bounds.lower_y, e.bounds.lower_z});
    grow(c.bounds, {e.bounds.upper_x, e.bounds.upper_y, e.bounds.upper_z});
  }
  for (std::uint32_t k = 0; k < clusters_.size(); ++k) {
    RTCGeometry g = rtcNewGeometry(scene_.device->handle(), RTC_GEOMETRY_TYPE_USER);
    if (!g) throw Error("Embree could not make a cluster of the merged scene");
    rtcSetGeometryUserPrimitiveCount(g, 1);
    rtcSetGeometryUserData(g, clusters_[k].get());
    rtcSetGeometryBoundsFunction(g, boundsOf, nullptr);
    rtcSetGeometryIntersectFunction(g, intersectCluster);
    rtcSetGeometryOccludedFunction(g, occludedCluster);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(merged, g, k);
    geometries_.push_back(g);
  }
  spdlog::debug("tsr::embree: merged scene streamed in {} clusters of {} instances", clusters_.size(), entries.size());
}

std::shared_ptr<const StreamedGeometry::Built> StreamedGeometry::acquire(Cluster& c) {
  if (auto held = c.built.load(std::memory_order_acquire)) {
    c.lastUse.store(clock_.fetch_add(1, std::memory_order_relaxed), std::memory_order_relaxed);
    return held;
  }
  std::shared_ptr<Built> made;
  bool built = false;
  {
    const std::lock_guard one(c.building);
    if (auto held = c.built.load(std::memory_order_acquire)) return held;  // built while this thread waited
    if (c.failed) return nullptr;
    if (!c.pending) {
      // The copies are made here, alone: no task scheduler runs under the lock.
      try {
        c.pending = make(c);
      } catch (const std::exception& e) {
        // Thrown into Embree's traversal it would end the program.
        fail(c, e.what());
        return nullptr;
      }
    }
    made = c.pending;
    // Threads that need the cluster meanwhile join this build (Embree
    // isolates it from the render's tasks), unless this device cannot.
    if (!parallelCommit_) built = commit(made);
  }
  if (parallelCommit_) built = commit(made);
  std::vector<std::shared_ptr<const Built>> dropped;  // released after the locks
  {
    const std::lock_guard one(c.building);
    // Another thread published it (and it may be dropped already: this
    // thread's copy is as good), or found that the build failed.
    if (c.pending != made) return built && !c.failed ? made : nullptr;
    c.pending.reset();
    if (!built) {
      fail(c, "Embree could not build its BVH");
      return nullptr;
    }
    const std::lock_guard held(cache_);
    ++builds_;
    heldBytes_ += made->bytes;
    c.built.store(made, std::memory_order_release);
    c.lastUse.store(clock_.fetch_add(1, std::memory_order_relaxed), std::memory_order_relaxed);
    dropped = evictOver(c);
  }
  return made;
}

std::shared_ptr<StreamedGeometry::Built> StreamedGeometry::make(const Cluster& c) const {
  auto b = std::make_shared<Built>();
  b->scene = rtcNewScene(scene_.device->handle());
  if (!b->scene) throw Error("Embree could not make a cluster scene");
  rtcSetSceneFlags(b->scene, RTC_SCENE_FLAG_COMPACT | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  rtcSetSceneBuildQuality(b->scene, RTC_BUILD_QUALITY_MEDIUM);
  for (std::uint32_t k = 0; k < c.instances.size(); ++k) {
    const InstanceRecord& inst = *scene_.instances[c.instances[k]];
    RTCGeometry g = worldGeometry(scene_.device->handle(), scene_.meshes[index(inst.mesh)]->data, inst.transform);
    rtcAttachGeometryByID(b->scene, g, k);
    rtcReleaseGeometry(g);
  }
  b->bytes = c.bytes;
  return b;
}

// Embree 3 keeps a thread's last error for it: one raised by the build
// (memory) is read here, where it can be told, not by an unrelated check.
bool StreamedGeometry::commit(const std::shared_ptr<Built>& made) const {
  rtcCommitScene(made->scene);
  return rtcGetDeviceError(scene_.device->handle()) == RTC_ERROR_NONE;
}

void StreamedGeometry::fail(Cluster& c, const char* why) {
  spdlog::error("tsr::embree: a cluster of {} instances is left out of the image: {}", c.instances.size(), why);
  c.failed = true;
}

// The least recently used cluster goes. Tiles sweep the image, so the
// clusters a tile's rays reach are mostly those of the tiles just before it
// (least frequently used, measured against it, made ten times the builds:
// the clusters just built, reached by few rays yet, went first).
std::vector<std::shared_ptr<const StreamedGeometry::Built>> StreamedGeometry::evictOver(const Cluster& keep) {
  std::vector<std::shared_ptr<const Built>> dropped;
  while (heldBytes_ > budget_.bytes) {
    Cluster* oldest = nullptr;
    for (const auto& c : clusters_)
      if (c.get() != &keep && c->built.load(std::memory_order_relaxed) &&
          (!oldest || c->lastUse.load(std::memory_order_relaxed) < oldest->lastUse.load(std::memory_order_relaxed)))
        oldest = c.get();
    if (!oldest) break;  // the one just built is over the budget alone
    dropped.push_back(oldest->built.exchange(nullptr));
    heldBytes_ -= dropped.back()->bytes;
    ++evictions_;
  }
  return dropped;
}

TraceMemoryUse StreamedGeometry::use() const {
  const std::lock_guard held(cache_);
  TraceMemoryUse u;
  u.streamed = true;
  u.clusters = std::uint32_t(clusters_.size());
  for (const auto& c : clusters_) u.built += c->built.load(std::memory_order_relaxed) ? 1 : 0;
  u.heldBytes = heldBytes_;
  u.builds = builds_;
  u.evictions = evictions_;
  return u;
}

}  // namespace tsr::embree
