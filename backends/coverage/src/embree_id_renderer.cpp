#include "tsr/cov/embree_id_renderer.hpp"
#include "tsr/backend/embree_triangles.hpp"

#include "tsr/backend/embree_device.hpp"
#include "tsr/backend/validate.hpp"
#include "tsr/cov/error.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>

namespace tsr::cov {

namespace {

// Its scene and geometry (EmbreeTriangles) are released with it.
struct MeshRecord : backend::EmbreeTriangles {
  MeshData data;
  std::uint32_t users = 0;
  bool dirty = true;
};

struct InstanceRecord {
  Instance desc;
  RTCGeometry geometry = nullptr;
  bool dirty = true;

  InstanceRecord() = default;
  InstanceRecord(const InstanceRecord&) = delete;
  InstanceRecord& operator=(const InstanceRecord&) = delete;
  ~InstanceRecord() {
    if (geometry) rtcReleaseGeometry(geometry);
  }
};

template <class Records, class Id>
auto& lookup(Records& records, Id id, const char* what) {
  const std::uint32_t i = index(id);
  if (i >= records.size() || !records[i]) throw Error(std::string("unknown ") + what + " id " + std::to_string(i));
  return *records[i];
}

void validateTransform(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) throw Error("instance transform contains NaN or infinity");
}

void validateObject(ObjectId object) {
  if (object == kBackground) throw Error("object id 0 is reserved for the background");
}

// (Re)creates the triangle geometry of a mesh from its data.
void fillGeometry(MeshRecord& m, RTCDevice device) {
  const MeshData& d = m.data;
  if (!m.fill(device, {reinterpret_cast<const float*>(d.positions.data()), 3 * d.positions.size()}, d.indices,
              d.usage == MeshUsage::Animated))
    throw Error("Embree could not allocate mesh buffers");
  m.dirty = true;
}

constexpr std::uint32_t kPacket = 4;  // 4x4 pixels per rtcIntersect16

}  // namespace

struct EmbreeIdRenderer::State {
  EmbreeIdSettings settings;
  backend::EmbreeDevice device{[](const std::string& message) { throw Error(message); }};
  RTCScene top = nullptr;
  std::vector<std::unique_ptr<MeshRecord>> meshes;
  std::vector<std::unique_ptr<InstanceRecord>> instances;
  // Instance slot (its geomID in the top scene) -> object; kBackground for
  // removed and transparent instances. Read by the ray loop.
  std::vector<ObjectId> objectOf;
  bool topDirty = true;
  std::optional<tbb::task_arena> arena;

  State() {
    top = rtcNewScene(device.handle());
    // The top level changes with every moved instance: favour fast rebuilds.
    rtcSetSceneFlags(top, RTC_SCENE_FLAG_DYNAMIC);
    rtcSetSceneBuildQuality(top, RTC_BUILD_QUALITY_LOW);
    device.check("scene creation");
  }
  ~State() {
    instances.clear();  // geometries go before the scenes they belong to
    meshes.clear();
    rtcReleaseScene(top);
  }
  void resetArena() {
    arena.emplace(settings.threads > 0 ? settings.threads : static_cast<int>(tbb::task_arena::automatic));
  }
  // A transparent instance is disabled in the top scene rather than masked:
  // it then costs no traversal at all, and neither occludes nor counts.
  void applyVisibility(InstanceRecord& inst, std::uint32_t slot) {
    if (inst.desc.transparent)
      rtcDisableGeometry(inst.geometry);
    else
      rtcEnableGeometry(inst.geometry);
    objectOf[slot] = inst.desc.transparent ? kBackground : inst.desc.object;
    topDirty = true;
  }
};

EmbreeIdRenderer::EmbreeIdRenderer(EmbreeIdSettings settings) : state_(std::make_unique<State>()) {
  setSettings(settings);
}

EmbreeIdRenderer::~EmbreeIdRenderer() = default;

void EmbreeIdRenderer::setSettings(const EmbreeIdSettings& settings) {
  if (settings.threads < 0) throw Error("threads must be 0 (all) or positive");
  if (settings.tileSize < kPacket || settings.tileSize % kPacket != 0)
    throw Error("tile size must be a positive multiple of " + std::to_string(kPacket));
  const bool threadsChanged = !state_->arena || settings.threads != state_->settings.threads;
  state_->settings = settings;
  if (threadsChanged) state_->resetArena();
}

const EmbreeIdSettings& EmbreeIdRenderer::settings() const { return state_->settings; }

namespace {
// Rays hit surfaces: a line or point of one pixel's width has none.
void traceable(const MeshData& data) {
  data.validate();
  if (data.primitive != Primitive::Triangles)
    throw Error("the Embree id pass draws no lines or points (the Vulkan one does: engine=vulkan)");
}
}  // namespace

MeshId EmbreeIdRenderer::addMesh(MeshData data) {
  traceable(data);
  auto m = std::make_unique<MeshRecord>();
  m->data = std::move(data);
  fillGeometry(*m, state_->device.handle());
  state_->device.check("addMesh");
  state_->meshes.push_back(std::move(m));
  return MeshId(state_->meshes.size() - 1);
}

void EmbreeIdRenderer::setMeshData(MeshId id, MeshData data) {
  auto& m = lookup(state_->meshes, id, "mesh");
  traceable(data);
  m.data = std::move(data);
  fillGeometry(m, state_->device.handle());
  state_->device.check("setMeshData");
}

void EmbreeIdRenderer::updateMeshVertices(MeshId id, const VertexEdit& edit) {
  auto& m = lookup(state_->meshes, id, "mesh");
  backend::validate<Error>(edit, m.data.positions.size());
  const auto positions = edit.changedPositions();
  for (const auto& p : positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw Error("vertex update contains NaN or infinity");
  if (!m.geometry) throw Error("mesh " + std::to_string(index(id)) + " has no geometry: its last setMeshData failed");
  std::copy(positions.begin(), positions.end(), m.data.positions.begin() + edit.first);
  auto* v = static_cast<glm::vec3*>(rtcGetGeometryBufferData(m.geometry, RTC_BUFFER_TYPE_VERTEX, 0));
  std::memcpy(v + edit.first, positions.data(), positions.size() * sizeof(glm::vec3));
  rtcUpdateGeometryBuffer(m.geometry, RTC_BUFFER_TYPE_VERTEX, 0);
  m.dirty = true;
}

void EmbreeIdRenderer::removeMesh(MeshId id) {
  auto& m = lookup(state_->meshes, id, "mesh");
  if (m.users > 0)
    throw Error("mesh " + std::to_string(index(id)) + " is still used by " + std::to_string(m.users) + " instance(s)");
  state_->meshes[index(id)].reset();
}

InstanceId EmbreeIdRenderer::addInstance(const Instance& instance) {
  auto& m = lookup(state_->meshes, instance.mesh, "mesh");
  validateTransform(instance.transform);
  validateObject(instance.object);
  auto inst = std::make_unique<InstanceRecord>();
  inst->desc = instance;
  inst->geometry = rtcNewGeometry(state_->device.handle(), RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(inst->geometry, m.scene);
  rtcSetGeometryTimeStepCount(inst->geometry, 1);
  rtcSetGeometryTransform(inst->geometry, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &instance.transform[0][0]);
  const auto slot = static_cast<std::uint32_t>(state_->instances.size());
  rtcAttachGeometryByID(state_->top, inst->geometry, slot);
  state_->device.check("addInstance");
  ++m.users;
  state_->objectOf.push_back(kBackground);
  state_->applyVisibility(*inst, slot);
  state_->instances.push_back(std::move(inst));
  return InstanceId(slot);
}

void EmbreeIdRenderer::setInstanceTransform(InstanceId id, const glm::mat4& transform) {
  auto& inst = lookup(state_->instances, id, "instance");
  validateTransform(transform);
  inst.desc.transform = transform;
  rtcSetGeometryTransform(inst.geometry, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &transform[0][0]);
  inst.dirty = true;
  state_->topDirty = true;
}

void EmbreeIdRenderer::setInstanceObject(InstanceId id, ObjectId object) {
  auto& inst = lookup(state_->instances, id, "instance");
  validateObject(object);
  inst.desc.object = object;
  // Only the lookup table changes; the acceleration structures stay.
  if (!inst.desc.transparent) state_->objectOf[index(id)] = object;
}

void EmbreeIdRenderer::setInstanceTransparent(InstanceId id, bool transparent) {
  auto& inst = lookup(state_->instances, id, "instance");
  if (inst.desc.transparent == transparent) return;
  inst.desc.transparent = transparent;
  state_->applyVisibility(inst, index(id));
}

void EmbreeIdRenderer::removeInstance(InstanceId id) {
  auto& inst = lookup(state_->instances, id, "instance");
  --state_->meshes[index(inst.desc.mesh)]->users;
  rtcDetachGeometry(state_->top, index(id));
  state_->instances[index(id)].reset();
  state_->objectOf[index(id)] = kBackground;
  state_->topDirty = true;
}

std::size_t EmbreeIdRenderer::meshCount() const {
  return static_cast<std::size_t>(
      std::count_if(state_->meshes.begin(), state_->meshes.end(), [](auto& m) { return m != nullptr; }));
}

std::size_t EmbreeIdRenderer::instanceCount() const {
  return static_cast<std::size_t>(
      std::count_if(state_->instances.begin(), state_->instances.end(), [](auto& i) { return i != nullptr; }));
}

void EmbreeIdRenderer::commit() {
  State& s = *state_;
  bool meshChanged = false;
  for (auto& m : s.meshes) {
    if (!m || !m->dirty) continue;
    rtcCommitGeometry(m->geometry);
    rtcCommitScene(m->scene);
    meshChanged = true;
  }
  for (auto& inst : s.instances) {
    if (!inst) continue;
    // An instance of a changed mesh has new bounds: Embree wants it committed again.
    if (meshChanged && s.meshes[index(inst->desc.mesh)]->dirty) inst->dirty = true;
    if (!inst->dirty) continue;
    rtcCommitGeometry(inst->geometry);
    inst->dirty = false;
  }
  if (meshChanged)
    for (auto& m : s.meshes)
      if (m) m->dirty = false;
  if (s.topDirty || meshChanged) {
    rtcCommitScene(s.top);
    s.topDirty = false;
  }
  s.device.check("commit");
}

IdBuffer EmbreeIdRenderer::render(const Camera& camera, const Region& region) {
  backend::validate<Error>(camera);
  backend::validate<Error>(region);
  commit();
  IdBuffer out(region);
  const State& s = *state_;
  const std::uint32_t ts = s.settings.tileSize;
  const std::uint32_t rw = region.regionWidth(), rh = region.regionHeight();
  const std::uint32_t tilesX = (rw + ts - 1) / ts, tilesY = (rh + ts - 1) / ts;
  const glm::vec3 origin(camera.cameraToWorld[3]);
  const glm::mat3 rotation(camera.cameraToWorld);
  // Pixel centres of the FULL image on the window at z = -near.
  const float dx = (camera.right - camera.left) / float(region.width);
  const float dy = (camera.top - camera.bottom) / float(region.height);

  auto renderTile = [&](std::size_t tile) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    const std::uint32_t xb = std::uint32_t(tile % tilesX) * ts, yb = std::uint32_t(tile / tilesX) * ts;
    const std::uint32_t xe = std::min(rw, xb + ts), ye = std::min(rh, yb + ts);
    alignas(64) RTCRayHit16 rays;
    alignas(64) int valid[16];
    for (std::uint32_t py = yb; py < ye; py += kPacket)
      for (std::uint32_t px = xb; px < xe; px += kPacket) {
        for (std::uint32_t lane = 0; lane < 16; ++lane) {
          const std::uint32_t x = px + lane % kPacket, y = py + lane / kPacket;
          valid[lane] = x < xe && y < ye ? -1 : 0;
          const float cx = camera.left + dx * (float(region.x0 + x) + 0.5f);
          const float cy = camera.top - dy * (float(region.y0 + y) + 0.5f);
          // Camera-space z of the direction is -near, so depth = t * near.
          const glm::vec3 d = rotation * glm::vec3(cx, cy, -camera.near);
          rays.ray.org_x[lane] = origin.x;
          rays.ray.org_y[lane] = origin.y;
          rays.ray.org_z[lane] = origin.z;
          rays.ray.dir_x[lane] = d.x;
          rays.ray.dir_y[lane] = d.y;
          rays.ray.dir_z[lane] = d.z;
          rays.ray.tnear[lane] = 0.0f;
          rays.ray.tfar[lane] = kNoDepth;
          rays.ray.time[lane] = 0.0f;
          rays.ray.mask[lane] = ~0u;
          rays.ray.id[lane] = lane;
          rays.ray.flags[lane] = 0;
          rays.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
          rays.hit.instID[0][lane] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect16(valid, s.top, &context, &rays);
        for (std::uint32_t lane = 0; lane < 16; ++lane) {
          if (!valid[lane]) continue;
          const std::uint32_t slot = rays.hit.instID[0][lane];
          if (slot == RTC_INVALID_GEOMETRY_ID) continue;
          const std::size_t i = out.index(px + lane % kPacket, py + lane / kPacket);
          out.ids[i] = s.objectOf[slot];
          out.depth[i] = rays.ray.tfar[lane] * camera.near;
        }
      }
  };

  state_->arena->execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, std::size_t{tilesX} * tilesY, 1),
        [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t t = r.begin(); t != r.end(); ++t) renderTile(t);
        },
        tbb::simple_partitioner());
  });
  return out;
}

}  // namespace tsr::cov
