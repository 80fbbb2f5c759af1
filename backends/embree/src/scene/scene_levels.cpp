#include "scene/scene_levels.hpp"

#include "scene/streamed_geometry.hpp"

#include "tsr/embree/error.hpp"

#include <spdlog/spdlog.h>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace tsr::embree {

namespace {

// Takes the instance's copy out of the top level, a ghost's included (which
// rebuilds the top level).
void leaveTop(SceneState& s, InstanceRecord& inst, std::uint32_t id) {
  rtcDetachGeometry(s.top, topId(id));
  --s.topInstances;
  s.topDirty = true;
  if (inst.level == Level::Ghosted) {
    s.ghosts[topId(id)] = 0;
    --s.ghostCount;
  }
}

void enterMoving(SceneState& s, InstanceRecord& inst, std::uint32_t id) {
  if (!inst.movingGeometry) {
    inst.movingGeometry = rtcNewGeometry(s.device->handle(), RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(inst.movingGeometry, s.meshes[index(inst.mesh)]->scene);
    rtcSetGeometryTimeStepCount(inst.movingGeometry, 1);
  }
  inst.movingId = std::uint32_t(s.movingIds.size());
  rtcAttachGeometryByID(s.moving, inst.movingGeometry, inst.movingId);
  s.movingIds.push_back(id);
  s.movingDirty = true;
}

void leaveMoving(SceneState& s, InstanceRecord& inst) {
  // Keep the moving level's ids dense: the last one takes the freed id.
  const std::uint32_t last = std::uint32_t(s.movingIds.size() - 1);
  rtcDetachGeometry(s.moving, inst.movingId);
  if (inst.movingId != last) {
    InstanceRecord& other = *s.instances[s.movingIds[last]];
    rtcDetachGeometry(s.moving, last);
    rtcAttachGeometryByID(s.moving, other.movingGeometry, inst.movingId);
    other.movingId = inst.movingId;
    s.movingIds[inst.movingId] = s.movingIds[last];
  }
  s.movingIds.pop_back();
  s.movingDirty = true;
}

}  // namespace

void unplace(SceneState& s, InstanceRecord& inst, std::uint32_t id) {
  switch (inst.level) {
    case Level::None:
      break;
    case Level::Merged:
      if (inst.flatGeometry) {  // streamed, it is in a cluster, which the next partition leaves out
        rtcDetachGeometry(s.merged, id);
        rtcReleaseGeometry(inst.flatGeometry);
        inst.flatGeometry = nullptr;
      }
      s.mergedDirty = true;
      break;
    case Level::Top:
      leaveTop(s, inst, id);
      break;
    case Level::Moving:
      leaveMoving(s, inst);
      break;
    case Level::Ghosted:
      leaveTop(s, inst, id);
      leaveMoving(s, inst);
      break;
  }
  inst.level = Level::None;
}

// The indices are the mesh's own, shared rather than copied: a mesh's data
// is replaced only by setMeshData, whose commit places this instance again
// before the merged scene (or a cluster of it) is built.
RTCGeometry worldGeometry(RTCDevice device, const MeshData& d, const glm::mat4& transform) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<glm::vec3*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(glm::vec3), d.positions.size()));
  if (!v) {
    rtcReleaseGeometry(g);
    throw Error("Embree could not allocate merged mesh buffers");
  }
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, d.indices.data(), 0,
                             3 * sizeof(std::uint32_t), d.indices.size() / 3);
  for (std::size_t k = 0; k < d.positions.size(); ++k) v[k] = glm::vec3(transform * glm::vec4(d.positions[k], 1.0f));
  rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
  rtcCommitGeometry(g);
  return g;
}

namespace {

bool inside(const RTCBounds& a, const RTCBounds& b) {
  return a.lower_x >= b.lower_x && a.lower_y >= b.lower_y && a.lower_z >= b.lower_z && a.upper_x <= b.upper_x &&
         a.upper_y <= b.upper_y && a.upper_z <= b.upper_z;
}

bool same(const RTCBounds& a, const RTCBounds& b) { return inside(a, b) && inside(b, a); }

RTCBounds sceneBounds(RTCScene scene) {
  RTCBounds b;
  rtcGetSceneBounds(scene, &b);
  return b;
}

// Whether an instance of the mesh is copied to world space in the merged scene.
bool merged(const SceneState& s, const MeshRecord& m) {
  return m.users.size() == 1 && s.instances[m.users.front()]->level == Level::Merged;
}

// Commit step 1: a changed mesh's own BVH. If the mesh stays inside the
// bounds its instances' levels were built with, nothing else changes (cost
// O(mesh), whatever its instance count). Otherwise it changes the bounds of
// every instance of it, which therefore join the moving level.
void spreadMeshEdits(SceneState& s) {
  for (std::uint32_t id : s.pending.meshes) {
    if (!s.meshes[id]) continue;
    MeshRecord& m = *s.meshes[id];
    m.dirty = false;
    m.sceneStale = true;
    if (m.users.empty()) continue;  // built when an instance needs it
    if (!m.filled()) {
      // Its one user is merged (or not placed yet): it is copied again.
      for (std::uint32_t u : m.users) s.mark(u, true);
      continue;
    }
    rtcCommitGeometry(m.geometry);
    rtcCommitScene(m.scene);
    m.sceneStale = false;
    const RTCBounds now = sceneBounds(m.scene);
    if (inside(now, m.levelBounds) && !merged(s, m)) {
      if (!m.shrunk && !same(now, m.levelBounds)) {
        m.shrunk = true;
        s.shrunkMeshes.push_back(id);
      }
      for (const EmissiveRange& r : s.emissiveRanges)
        s.pending.emitters |= s.instances[r.instance] && index(s.instances[r.instance]->mesh) == id;
      continue;
    }
    m.levelBounds = now;  // every level holding a user rebuilds below
    for (std::uint32_t u : m.users) {
      s.instances[u]->moved = true;
      s.instances[u]->meshChanged = true;
      s.mark(u, true);
    }
  }
}

void setTransform(RTCGeometry g, const glm::mat4& transform) {
  rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &transform[0][0]);
}

// The moving level's copy: two time steps (frame start and end) while the
// instance moves over the frame interval, Embree interpolating between as
// InstanceMotion says.
void setMovingTransform(const InstanceRecord& inst) {
  rtcSetGeometryTimeStepCount(inst.movingGeometry, inst.motion ? 2 : 1);
  if (!inst.motion) return setTransform(inst.movingGeometry, inst.transform);
  for (int step = 0; step < 2; ++step) {
    const RTCQuaternionDecomposition d = inst.motion->step(step);
    rtcSetGeometryTransformQuaternion(inst.movingGeometry, unsigned(step), &d);
  }
}

// Commit step 2: each changed instance goes where it belongs: static meshes
// nobody else uses into the merged scene, instances that moved into the
// moving level, the rest into the top level. An instance that moves out of
// the top level leaves a ghost there instead of rebuilding it, unless its
// mesh changed (the ghost would trace the new mesh, with bounds of the old).
// Returns the instanced ones.
std::vector<std::uint32_t> placeInstances(SceneState& s) {
  std::vector<std::uint32_t> instanced;
  for (std::uint32_t id : s.pending.instances) {
    if (!s.instances[id] || !s.instances[id]->placeDirty) continue;
    InstanceRecord& inst = *s.instances[id];
    const MeshRecord& m = *s.meshes[index(inst.mesh)];
    inst.placeDirty = false;
    const bool inTop = inst.level == Level::Top || inst.level == Level::Ghosted;
    // An instance moving over the frame interval needs two time steps,
    // which only the moving level's copy has.
    const Level want = inst.motion                                                ? Level::Moving
                       : m.data.usage == MeshUsage::Static && m.users.size() == 1 ? Level::Merged
                       : !inst.moved                                              ? Level::Top
                       : inTop && !inst.meshChanged                               ? Level::Ghosted
                                                                                  : Level::Moving;
    inst.meshChanged = false;
    switch (want) {
      case Level::Merged:
        // A merged copy is in world space: any change rebuilds it.
        unplace(s, inst, id);
        if (!s.streamed) {  // streamed, the partition puts it in a cluster
          inst.flatGeometry = worldGeometry(s.device->handle(), m.data, inst.transform);
          rtcAttachGeometryByID(s.merged, inst.flatGeometry, id);
        }
        s.mergedDirty = true;
        break;
      case Level::Top:
        if (inst.level != Level::Top) {
          unplace(s, inst, id);
          setTransform(inst.geometry, inst.transform);
          rtcAttachGeometryByID(s.top, inst.geometry, topId(id));
          ++s.topInstances;
          s.topDirty = true;
        }
        instanced.push_back(id);
        break;
      case Level::Ghosted:
        if (inst.level == Level::Top) {
          if (s.ghosts.size() <= topId(id)) s.ghosts.resize(s.instances.size() + 1);
          s.ghosts[topId(id)] = 1;
          ++s.ghostCount;
          enterMoving(s, inst, id);
        }
        setMovingTransform(inst);
        s.movingDirty = true;
        instanced.push_back(id);
        break;
      case Level::Moving:
        if (inst.level == Level::Ghosted) {
          leaveTop(s, inst, id);
        } else if (inst.level != Level::Moving) {
          unplace(s, inst, id);
          enterMoving(s, inst, id);
        }
        setMovingTransform(inst);
        s.movingDirty = true;
        instanced.push_back(id);
        break;
      case Level::None:
        break;
    }
    inst.level = want;
  }
  return instanced;
}

// How many ghosts the top level carries before it rebuilds. Each edit
// rebuilds the moving level over its L ghosts (c L, c about 0.7 us here),
// each L-th folds them, rebuilding the top level over all n instances
// (about 2c n): the mean cost per edit, 2c n / L + c L / 2, is least at
// L = 2 sqrt(n).
std::uint32_t ghostLimit(std::uint32_t topInstances) {
  return std::max<std::uint32_t>(32, std::uint32_t(2.0 * std::sqrt(double(topInstances))));
}

// Commit step 3a: when the top level rebuilds anyway, or the ghosts grew too
// many, the ghosted instances go back to the top level at their transform.
void foldGhosts(SceneState& s) {
  if (s.ghostCount == 0 || (!s.topDirty && s.ghostCount <= ghostLimit(s.topInstances))) return;
  std::vector<std::uint32_t> ghosted;
  for (std::uint32_t id : s.movingIds)
    if (s.instances[id]->level == Level::Ghosted) ghosted.push_back(id);
  for (std::uint32_t id : ghosted) {
    InstanceRecord& inst = *s.instances[id];
    leaveMoving(s, inst);
    s.ghosts[topId(id)] = 0;
    inst.level = Level::Top;
    inst.moved = false;
    setTransform(inst.geometry, inst.transform);
    rtcCommitGeometry(inst.geometry);
  }
  s.ghostCount = 0;
  s.topDirty = true;
}

// A merged scene this large is built compact (Embree's indexed triangles,
// no spatial splits): its BVH takes about half the memory (a 5 M-triangle
// plant: 227 MB less) and builds faster, for some 10 % slower tracing.
// Below it, memory is not what binds and the faster BVH is kept. The hits
// are the same but for rays through a shared edge or vertex, which may take
// the neighbour (a 2 M-triangle plant at 256x256, 16 spp: one pixel in
// 65,536 differed, by 0.011).
constexpr std::uint64_t kCompactMergedTriangles = 1u << 20;

RTCSceneFlags mergedSceneFlags(const SceneState& s) {
  std::uint64_t triangles = 0;
  for (const auto& inst : s.instances)
    if (inst && inst->level == Level::Merged) triangles += s.meshes[index(inst->mesh)]->data.indices.size() / 3;
  return triangles >= kCompactMergedTriangles ? RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION | RTC_SCENE_FLAG_COMPACT
                                              : RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION;
}

// Commit step 3b: the BVH of each mesh an instance traverses, then the
// instances (whose bounds come from it), then the levels over them.
void buildLevels(SceneState& s, const std::vector<std::uint32_t>& instanced) {
  for (std::uint32_t id : instanced) {
    MeshRecord& m = *s.meshes[index(s.instances[id]->mesh)];
    if (!m.filled()) m.fill(s.device->handle());
    if (!m.sceneStale) continue;
    rtcCommitGeometry(m.geometry);
    rtcCommitScene(m.scene);
    m.sceneStale = false;
    m.levelBounds = sceneBounds(m.scene);  // no level held it while stale
  }
  for (std::uint32_t id : instanced) {
    const InstanceRecord& inst = *s.instances[id];
    rtcCommitGeometry(inst.level == Level::Top ? inst.geometry : inst.movingGeometry);
  }
  if (s.mergedDirty) {
    if (s.streamed) s.streamed->partition(s.merged);
    rtcSetSceneFlags(s.merged, s.streamed ? RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION : mergedSceneFlags(s));
    rtcCommitScene(s.merged);
    rtcCommitGeometry(s.mergedInstance);
    s.mergedDirty = false;
    s.topDirty = true;
  }
  foldGhosts(s);
  const bool rebuilt = s.topDirty || s.movingDirty;
  if (s.topDirty) {
    rtcCommitScene(s.top);
    s.topDirty = false;
  }
  if (s.movingDirty) {
    rtcCommitScene(s.moving);
    s.movingDirty = false;
  }
  if (rebuilt) {
    for (std::uint32_t id : s.shrunkMeshes) {
      if (!s.meshes[id] || !s.meshes[id]->shrunk) continue;
      s.meshes[id]->levelBounds = sceneBounds(s.meshes[id]->scene);
      s.meshes[id]->shrunk = false;
    }
    s.shrunkMeshes.clear();
  }
  // Without instances there is no top level to cross.
  s.traversable = s.topInstances > 0 ? s.top : s.merged;
  s.movingTraversable = s.movingIds.empty() ? nullptr : s.moving;
  s.device->check("commit");
}

// Whether an instance belongs in the merged scene (placeInstances' rule).
bool mergeable(const SceneState& s, const InstanceRecord& inst) {
  const MeshRecord& m = *s.meshes[index(inst.mesh)];
  return !inst.motion && m.data.usage == MeshUsage::Static && m.users.size() == 1;
}

// Whether this commit may change what the merged scene holds (then it is
// rebuilt anyway, at a cost of all its triangles, beside which counting
// its instances is small).
bool mergedMayChange(const SceneState& s) {
  if (s.traceMemoryChanged || !s.pending.meshes.empty()) return true;
  for (std::uint32_t id : s.pending.instances)
    if (!s.instances[id] || s.instances[id]->level == Level::Merged || mergeable(s, *s.instances[id])) return true;
  return false;
}

// Commit step 0: the merged scene built whole, or streamed by clusters when
// its estimated size passes the trace memory budget. A change of form
// places every merged instance again.
void chooseMergedForm(SceneState& s) {
  if (!mergedMayChange(s)) return;
  s.traceMemoryChanged = false;
  std::uint64_t bytes = 0, triangles = 0;
  for (const auto& inst : s.instances) {
    if (!inst || !mergeable(s, *inst)) continue;
    const MeshData& d = s.meshes[index(inst->mesh)]->data;
    bytes += mergedBytes(d.positions.size(), d.indices.size() / 3);
    triangles += d.indices.size() / 3;
  }
  s.mergedEstimate = bytes;
  const bool streamed = bytes > s.traceMemory.bytes;
  if (streamed ? s.streamed && s.streamed->budget() == s.traceMemory : !s.streamed) return;
  for (std::uint32_t id = 0; id < s.instances.size(); ++id) {
    if (!s.instances[id] || s.instances[id]->level != Level::Merged) continue;
    unplace(s, *s.instances[id], id);
    s.mark(id, true);
  }
  if (s.streamed) s.streamed->detach(s.merged);
  s.streamed = streamed ? std::make_unique<StreamedGeometry>(s, s.traceMemory) : nullptr;
  s.mergedDirty = true;
  if (streamed) {
    spdlog::info(
        "tsr::embree: the merged scene ({} triangles, about {:.1f} GB) is over the trace memory ({:.1f} GB): it is "
        "built in clusters of about {} triangles as rays reach them, the least recently used dropped",
        triangles, double(bytes) * 1e-9, double(s.traceMemory.bytes) * 1e-9, s.traceMemory.clusterTriangles);
  }
}

}  // namespace

void commitLevels(SceneState& s) {
  chooseMergedForm(s);
  spreadMeshEdits(s);
  buildLevels(s, placeInstances(s));
}

}  // namespace tsr::embree
