#include "tsr/embree/scene.hpp"
#include "tsr/backend/embree_triangles.hpp"
#include "tsr/backend/validate.hpp"

#include "limits.hpp"
#include "scene/scene_levels.hpp"
#include "scene/scene_state.hpp"
#include "scene/streamed_geometry.hpp"
#include "tsr/embree/error.hpp"
#include "tsr/embree/sampling.hpp"

#include <spdlog/spdlog.h>
#include <glm/common.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

namespace tsr::embree {

namespace {

std::atomic<std::uint64_t> nextSceneUid{1};

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite(const glm::vec2& v) { return std::isfinite(v.x) && std::isfinite(v.y); }
bool traceable(const glm::vec3& p) {
  return withinCoordinateLimit(p.x) && withinCoordinateLimit(p.y) && withinCoordinateLimit(p.z);
}

void validateTransform(const glm::mat4& m) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (!withinCoordinateLimit(m[i][j]))
        throw Error("instance transform contains NaN, infinity or a value beyond 1e12 (kMaxCoordinate)");
  if (m[0][3] != 0.0f || m[1][3] != 0.0f || m[2][3] != 0.0f || m[3][3] != 1.0f) {
    throw Error("instance transform must be affine (last row 0 0 0 1)");
  }
  if (std::abs(glm::determinant(glm::mat3(m))) < 1e-20f) throw Error("instance transform is singular");
}

void validateMesh(const MeshData& d) {
  if (d.positions.empty()) throw Error("mesh has no positions");
  if (d.indices.empty() || d.indices.size() % 3 != 0) {
    throw Error("mesh index count " + std::to_string(d.indices.size()) + " is not a positive multiple of 3");
  }
  if (!d.normals.empty() && d.normals.size() != d.positions.size()) {
    throw Error("mesh has " + std::to_string(d.normals.size()) + " normals for " + std::to_string(d.positions.size()) +
                " positions");
  }
  if (!d.uvs.empty() && d.uvs.size() != d.positions.size()) {
    throw Error("mesh has " + std::to_string(d.uvs.size()) + " uvs for " + std::to_string(d.positions.size()) +
                " positions");
  }
  for (std::size_t i = 0; i < d.indices.size(); ++i) {
    if (d.indices[i] >= d.positions.size()) {
      throw Error("mesh index " + std::to_string(i) + " = " + std::to_string(d.indices[i]) + " is out of range (" +
                  std::to_string(d.positions.size()) + " positions)");
    }
  }
  for (const auto& p : d.positions)
    if (!traceable(p)) throw Error("mesh position contains NaN, infinity or a value beyond 1e12 (kMaxCoordinate)");
  for (const auto& n : d.normals)
    if (!finite(n)) throw Error("mesh normal contains NaN or infinity");
  for (const auto& t : d.uvs)
    if (!finite(t)) throw Error("mesh uv contains NaN or infinity");
}

void validateColour(const glm::vec3& c, const char* what) {
  if (!finite(c) || c.x < 0.0f || c.y < 0.0f || c.z < 0.0f) {
    throw Error(std::string("material ") + what + " must be finite and non-negative");
  }
}

void validateMedium(const Medium& m, const char* what) {
  for (const glm::vec3& c : {m.absorption, m.scattering, m.emission})
    if (!finite(c) || c.x < 0.0f || c.y < 0.0f || c.z < 0.0f)
      throw Error(std::string(what) + " coefficients must be finite and non-negative");
  if (!(m.g > -1.0f && m.g < 1.0f)) throw Error(std::string(what) + " phase g must lie strictly between -1 and 1");
}

template <class Vec, class Id>
auto& lookup(Vec& v, Id id, const char* what) {
  std::uint32_t i = index(id);
  if (i >= v.size() || !v[i]) throw Error(std::string("unknown ") + what + " id " + std::to_string(i));
  return v[i];
}

// The instances of a mesh whose user count crossed one: the merged copy is
// only for meshes used once.
void replaceUsers(SceneState& s, const MeshRecord& m) {
  if (m.users.size() > 2) return;
  for (std::uint32_t u : m.users) s.mark(u, true);
}

}  // namespace

void MeshRecord::fill(RTCDevice device) {
  const MeshData& d = data;
  // Every scene a top-level ray enters allows the tracer's context filter (ghosts).
  if (!EmbreeTriangles::fill(device, {reinterpret_cast<const float*>(d.positions.data()), 3 * d.positions.size()},
                             d.indices, d.usage == MeshUsage::Animated, RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION))
    throw Error("Embree could not allocate mesh buffers");
  sceneStale = true;
}

void SceneState::mark(std::uint32_t id, bool placed) {
  if (!instances[id]) {
    pending.instances.push_back(id);  // removed: its view is cleared
    return;
  }
  InstanceRecord& inst = *instances[id];
  inst.placeDirty |= placed;
  if (!inst.viewDirty) pending.instances.push_back(id);
  inst.viewDirty = true;
}

void SceneState::edit(const Edit& e) {
  ++version;
  if (!e.placementOnly) ++appearance;
  if (e.instance != kNoId) mark(e.instance, e.placed);
  if (e.mesh != kNoId && meshes[e.mesh] && !meshes[e.mesh]->dirty) {
    meshes[e.mesh]->dirty = true;
    pending.meshes.push_back(e.mesh);
  }
  pending.materials |= e.materials;
  pending.lights |= e.lights;
  pending.emitters |= e.emitters;
}

Scene::Scene(std::shared_ptr<Device> device) : state_(std::make_unique<SceneState>()) {
  if (!device) throw Error("scene needs a device");
  state_->device = std::move(device);
  state_->uid = nextSceneUid.fetch_add(1);
  state_->top = rtcNewScene(state_->device->handle());
  // Instances come and go rarely, but a whole scene arrives at once: favour fast builds.
  // The context filter is how the tracer skips ghosts (SceneState::ghosts);
  // Embree checks the flag of each scene a ray enters.
  rtcSetSceneFlags(state_->top, RTC_SCENE_FLAG_DYNAMIC | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  rtcSetSceneBuildQuality(state_->top, RTC_BUILD_QUALITY_LOW);
  state_->moving = rtcNewScene(state_->device->handle());
  rtcSetSceneFlags(state_->moving, RTC_SCENE_FLAG_DYNAMIC | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  rtcSetSceneBuildQuality(state_->moving, RTC_BUILD_QUALITY_LOW);
  state_->merged = rtcNewScene(state_->device->handle());  // its flags are set at each build (mergedSceneFlags)
  rtcSetSceneBuildQuality(state_->merged, RTC_BUILD_QUALITY_HIGH);
  state_->mergedInstance = rtcNewGeometry(state_->device->handle(), RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(state_->mergedInstance, state_->merged);
  rtcSetGeometryTimeStepCount(state_->mergedInstance, 1);
  const glm::mat4 identity(1.0f);
  rtcSetGeometryTransform(state_->mergedInstance, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &identity[0][0]);
  rtcAttachGeometryByID(state_->top, state_->mergedInstance, kMergedTopId);
  state_->device->check("scene creation");
}

Scene::~Scene() {
  // Geometries must go before the scenes they belong to.
  state_->instances.clear();
  state_->meshes.clear();
  if (state_->streamed) state_->streamed->detach(state_->merged);
  state_->streamed.reset();
  rtcReleaseGeometry(state_->mergedInstance);
  rtcReleaseScene(state_->merged);
  rtcReleaseScene(state_->moving);
  rtcReleaseScene(state_->top);
}

MeshId Scene::addMesh(MeshData data) {
  validateMesh(data);
  auto m = std::make_unique<MeshRecord>();
  m->scene = rtcNewScene(state_->device->handle());  // filled when an instance traverses it
  state_->device->check("addMesh");
  if (!m->scene) throw Error("Embree could not make a mesh scene");
  m->data = std::move(data);
  state_->meshes.push_back(std::move(m));
  state_->edit({});
  return MeshId(state_->meshes.size() - 1);
}

void Scene::updateMeshVertices(MeshId id, const VertexEdit& edit) {
  auto& m = *lookup(state_->meshes, id, "mesh");
  backend::validate<Error>(edit, m.data.positions.size());
  if (!edit.normals.empty() && m.data.normals.empty()) throw Error("mesh has no normals to update");
  const auto positions = edit.changedPositions();
  const auto normals = edit.changedNormals();
  for (const auto& p : positions)
    if (!traceable(p)) throw Error("vertex update contains NaN, infinity or a value beyond 1e12 (kMaxCoordinate)");
  for (const auto& v : normals)
    if (!finite(v)) throw Error("normal update contains NaN or infinity");
  // Shared arrays (a replica's) are copied before the first edit: the giver applies its edits itself.
  const std::span<glm::vec3> heldPositions = m.data.positions.writable();
  std::copy(positions.begin(), positions.end(), heldPositions.begin() + edit.first);
  if (!normals.empty()) std::copy(normals.begin(), normals.end(), m.data.normals.writable().begin() + edit.first);
  if (m.filled()) {
    auto* v = static_cast<glm::vec3*>(rtcGetGeometryBufferData(m.geometry, RTC_BUFFER_TYPE_VERTEX, 0));
    std::memcpy(v + edit.first, positions.data(), positions.size() * sizeof(glm::vec3));
    rtcUpdateGeometryBuffer(m.geometry, RTC_BUFFER_TYPE_VERTEX, 0);
  }
  state_->edit({.mesh = index(id)});
}

void Scene::setMeshData(MeshId id, MeshData data) {
  auto& m = *lookup(state_->meshes, id, "mesh");
  validateMesh(data);
  m.data = std::move(data);
  m.sceneStale = true;
  // Recorded first: the merged copy of a user shares the old indices, and
  // the next commit must place it again even when the fill below throws.
  state_->edit({.mesh = index(id)});
  if (m.filled()) {
    m.fill(state_->device->handle());
    state_->device->check("setMeshData");
  }
}

void Scene::removeMesh(MeshId id) {
  auto& m = lookup(state_->meshes, id, "mesh");
  if (!m->users.empty()) {
    throw Error("mesh " + std::to_string(index(id)) + " is still used by " + std::to_string(m->users.size()) +
                " instance(s)");
  }
  m.reset();
  state_->edit({});
}

InstanceId Scene::addInstance(MeshId mesh, MaterialId material, const glm::mat4& transform) {
  auto& m = *lookup(state_->meshes, mesh, "mesh");
  lookup(state_->materials, material, "material");
  validateTransform(transform);
  auto inst = std::make_unique<InstanceRecord>();
  inst->mesh = mesh;
  inst->material = material;
  inst->transform = transform;
  inst->geometry = rtcNewGeometry(state_->device->handle(), RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(inst->geometry, m.scene);
  rtcSetGeometryTimeStepCount(inst->geometry, 1);
  state_->device->check("addInstance");
  auto id = std::uint32_t(state_->instances.size());
  state_->instances.push_back(std::move(inst));
  m.users.push_back(id);
  state_->edit({.instance = id, .placed = true});
  replaceUsers(*state_, m);
  return InstanceId(id);
}

void Scene::setInstanceTransform(InstanceId id, const glm::mat4& transform) {
  setInstanceTransform(id, transform, transform);
}

void Scene::setInstanceTransform(InstanceId id, const glm::mat4& transform, const glm::mat4& atEnd) {
  auto& inst = *lookup(state_->instances, id, "instance");
  validateTransform(transform);
  validateTransform(atEnd);
  inst.transform = transform;
  inst.motion = atEnd != transform ? std::make_unique<InstanceMotion>(transform, atEnd) : nullptr;
  inst.moved = true;  // commit() gives the transform to the copy in the level it goes to
  state_->edit({.instance = index(id), .placed = true, .placementOnly = true});
}

void Scene::setInstanceMaterial(InstanceId id, MaterialId material) {
  auto& inst = *lookup(state_->instances, id, "instance");
  lookup(state_->materials, material, "material");
  inst.material = material;
  state_->edit({.instance = index(id)});
}

void Scene::removeInstance(InstanceId id) {
  auto& inst = lookup(state_->instances, id, "instance");
  unplace(*state_, *inst, index(id));
  auto& m = *state_->meshes[index(inst->mesh)];
  std::erase(m.users, index(id));
  inst.reset();
  state_->edit({.instance = index(id)});
  replaceUsers(*state_, m);
}

static void validateMaterial(const Material& m, const SceneState& s) {
  validateColour(m.baseColor, "baseColor");
  validateColour(m.emission, "emission");
  if (!(m.roughness >= 0.0f && m.roughness <= 1.0f)) throw Error("material roughness must be in [0, 1]");
  if (!(m.ior > 0.0f) || !std::isfinite(m.ior)) throw Error("material ior must be positive and finite");
  if (!(m.opacity >= 0.0f && m.opacity <= 1.0f)) throw Error("material opacity must be in [0, 1]");
  if (!std::isfinite(m.alphaCutoff)) throw Error("material alphaCutoff must be finite");
  for (const UvTransform& t : {m.baseColorUv, m.emissionUv, m.metallicRoughnessUv, m.transmissionUv, m.normalUv})
    if (!finite(t.row0) || !finite(t.row1)) throw Error("material uv transform contains NaN or infinity");
  std::optional<TextureId> none;
  const Medium& v = m.interior ? *m.interior : Medium{};
  if (!(m.metallic >= 0.0f && m.metallic <= 1.0f)) throw Error("material metallic must be in [0, 1]");
  if (!(m.specular >= 0.0f && m.specular <= 1.0f)) throw Error("material specular must be in [0, 1]");
  if (!(m.transmission >= 0.0f && m.transmission <= 1.0f)) throw Error("material transmission must be in [0, 1]");
  if (!std::isfinite(m.normalScale)) throw Error("material normalScale must be finite");
  for (const auto& t : {m.baseColorTexture, m.emissionTexture, m.metallicRoughnessTexture, m.transmissionTexture,
                        m.normalTexture, m.interior ? v.absorptionTexture : none,
                        m.interior ? v.scatteringTexture : none, m.interior ? v.emissionTexture : none}) {
    if (t && (index(*t) >= s.textures.size() || !s.textures[index(*t)])) {
      throw Error("material references unknown texture id " + std::to_string(index(*t)));
    }
  }
  if (m.interior) validateMedium(*m.interior, "material interior");
}

MaterialId Scene::addMaterial(const Material& material) {
  validateMaterial(material, *state_);
  state_->materials.emplace_back(material);
  state_->edit({.materials = true});
  return MaterialId(state_->materials.size() - 1);
}

void Scene::setMaterial(MaterialId id, const Material& material) {
  auto& slot = lookup(state_->materials, id, "material");
  validateMaterial(material, *state_);
  const bool emission = slot->isEmissive() || material.isEmissive();
  slot = material;
  state_->edit({.materials = true, .emitters = emission});
}

void Scene::removeMaterial(MaterialId id) {
  auto& slot = lookup(state_->materials, id, "material");
  for (const auto& inst : state_->instances) {
    if (inst && inst->material == id) throw Error("material " + std::to_string(index(id)) + " is still in use");
  }
  slot.reset();
  state_->edit({.materials = true});
}

TextureId Scene::addTexture(Texture texture) {
  state_->textures.push_back(std::make_shared<const Texture>(std::move(texture)));
  state_->edit({});
  return TextureId(state_->textures.size() - 1);
}

void Scene::removeTexture(TextureId id) {
  auto& slot = lookup(state_->textures, id, "texture");
  for (const auto& m : state_->materials) {
    const bool interior = m && m->interior &&
                          (m->interior->absorptionTexture == id || m->interior->scatteringTexture == id ||
                           m->interior->emissionTexture == id);
    const bool surface =
        m && (m->baseColorTexture == id || m->emissionTexture == id || m->metallicRoughnessTexture == id ||
              m->transmissionTexture == id || m->normalTexture == id);
    if (surface || interior) {
      throw Error("texture " + std::to_string(index(id)) + " is still used by a material");
    }
  }
  slot.reset();
  state_->edit({});
}

static void validateLight(const Light& light) {
  auto check = [](const glm::vec3& v, const char* what) {
    if (!finite(v)) throw Error(std::string("light ") + what + " contains NaN or infinity");
  };
  std::visit(
      [&](const auto& l) {
        using T = std::decay_t<decltype(l)>;
        if constexpr (std::is_same_v<T, PointLight>) {
          check(l.position, "position");
          validateColour(l.intensity, "(light intensity)");
        } else if constexpr (std::is_same_v<T, SpotLight>) {
          check(l.position, "position");
          check(l.direction, "direction");
          validateColour(l.intensity, "(light intensity)");
          if (glm::length(l.direction) <= 0.0f) throw Error("spot light direction is zero");
          if (!(l.innerAngle >= 0.0f && l.innerAngle <= l.outerAngle && l.outerAngle < kPi)) {
            throw Error("spot light angles must satisfy 0 <= inner <= outer < pi");
          }
        } else {
          check(l.direction, "direction");
          validateColour(l.irradiance, "(light irradiance)");
          if (glm::length(l.direction) <= 0.0f) throw Error("directional light direction is zero");
        }
      },
      light);
}

LightId Scene::addLight(const Light& light) {
  validateLight(light);
  state_->lights.emplace_back(light);
  state_->edit({.lights = true});
  return LightId(state_->lights.size() - 1);
}

void Scene::setLight(LightId id, const Light& light) {
  auto& slot = lookup(state_->lights, id, "light");
  validateLight(light);
  slot = light;
  state_->edit({.lights = true});
}

void Scene::removeLight(LightId id) {
  lookup(state_->lights, id, "light").reset();
  state_->edit({.lights = true});
}

void Scene::setEnvironment(Environment environment) {
  state_->environment = std::move(environment);
  state_->edit({});
}

namespace {
// Commit step 4: materials as the renderer reads them. Returns whether they
// moved in memory (every view points into them).
bool refreshMaterials(SceneState& s) {
  const ResolvedMaterial* before = s.resolved.data();
  s.resolved.resize(s.materials.size());
  s.materialMedia = false;
  s.texturedMedia = false;
  s.alphaTested = false;
  for (std::size_t i = 0; i < s.materials.size(); ++i) {
    auto& r = s.resolved[i];
    r = {};
    if (!s.materials[i]) continue;
    r.material = *s.materials[i];
    s.materialMedia = s.materialMedia || r.material.interior.has_value();
    if (r.material.baseColorTexture) r.baseColorTexture = s.textures[index(*r.material.baseColorTexture)].get();
    if (r.material.emissionTexture) r.emissionTexture = s.textures[index(*r.material.emissionTexture)].get();
    const bool partial = r.material.opacity < 1.0f || (r.baseColorTexture && !r.baseColorTexture->opaque());
    r.alphaTested = r.material.alphaMode != AlphaMode::Opaque && partial;
    s.alphaTested = s.alphaTested || r.alphaTested;
    auto surfaceTexture = [&](const std::optional<TextureId>& t) { return t ? s.textures[index(*t)].get() : nullptr; };
    r.metallicRoughnessTexture = surfaceTexture(r.material.metallicRoughnessTexture);
    r.transmissionTexture = surfaceTexture(r.material.transmissionTexture);
    r.normalTexture = surfaceTexture(r.material.normalTexture);
    if (r.material.interior && r.material.interior->textured()) {
      const Medium& m = *r.material.interior;
      auto texture = [&](const std::optional<TextureId>& t) { return t ? s.textures[index(*t)].get() : nullptr; };
      r.interior =
          VolumeField(m, texture(m.absorptionTexture), texture(m.scatteringTexture), texture(m.emissionTexture));
      s.texturedMedia = true;
    }
  }
  return s.resolved.data() != before;
}

InstanceView viewOf(const SceneState& s, const InstanceRecord& inst) {
  InstanceView v;
  v.mesh = &s.meshes[index(inst.mesh)]->data;
  v.transform = inst.transform;
  v.normalTransform = glm::transpose(glm::inverse(glm::mat3(inst.transform)));
  v.faceNormalTransform = glm::determinant(glm::mat3(inst.transform)) * v.normalTransform;
  v.motion = inst.motion.get();
  v.material = &s.resolved[index(inst.material)];
  if (v.material->interior.active() && !v.mesh->positions.empty()) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (const glm::vec3& p : v.mesh->positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const glm::vec3 size = glm::max(hi - lo, glm::vec3(1e-30f));
    glm::mat4 unit(1.0f);
    for (int a = 0; a < 3; ++a) unit[a][a] = 1.0f / size[a], unit[3][a] = -lo[a] / size[a];
    v.worldToVolume = unit * glm::inverse(inst.transform);
  }
  return v;
}

// Commit step 5: the views of the changed instances (of all if `all`). An
// emitter that changes, appears or goes rebuilds the emitter distribution.
void refreshViews(SceneState& s, bool all) {
  s.views.resize(s.instances.size());
  auto refresh = [&](std::uint32_t id) {
    InstanceView& v = s.views[id];
    bool emissive = v.emissiveOffset != kNotEmissive;
    v = s.instances[id] ? viewOf(s, *s.instances[id]) : InstanceView{};
    emissive |= v.material && v.material->material.isEmissive();
    s.pending.emitters |= emissive;
  };
  if (all) {
    for (std::uint32_t id = 0; id < s.instances.size(); ++id) refresh(id);
  } else {
    for (std::uint32_t id : s.pending.instances) refresh(id);
  }
  for (std::uint32_t id : s.pending.instances)
    if (s.instances[id]) s.instances[id]->viewDirty = false;
}

// Commit step 6: emissive triangles in world space, in instance-id order, so
// a scene rebuilt from scratch in the same order samples identically.
void rebuildEmitters(SceneState& s) {
  s.emissiveRanges.clear();
  s.emitterTriangles.clear();
  std::vector<float> power;
  for (std::size_t i = 0; i < s.views.size(); ++i) {
    auto& v = s.views[i];
    v.emissiveOffset = kNotEmissive;
    if (!v.mesh || !v.material->material.isEmissive() || v.motion) continue;
    v.emissiveOffset = std::uint32_t(power.size());
    s.emissiveRanges.push_back({v.emissiveOffset, std::uint32_t(i)});
    float lum = luminance(v.material->material.emission);
    const auto& d = *v.mesh;
    for (std::size_t t = 0; t < d.indices.size(); t += 3) {
      glm::vec3 p0 = glm::vec3(v.transform * glm::vec4(d.positions[d.indices[t]], 1.0f));
      glm::vec3 p1 = glm::vec3(v.transform * glm::vec4(d.positions[d.indices[t + 1]], 1.0f));
      glm::vec3 p2 = glm::vec3(v.transform * glm::vec4(d.positions[d.indices[t + 2]], 1.0f));
      EmitterTriangle tri{p0, p1 - p0, p2 - p0, glm::vec3(0.0f), 0.0f};
      glm::vec3 n = glm::cross(tri.e1, tri.e2);
      float len = glm::length(n);
      tri.area = 0.5f * len;
      if (len > 0.0f) tri.normal = n / len;
      s.emitterTriangles.push_back(tri);
      power.push_back(lum * tri.area);
    }
  }
  s.emitters = Distribution1D(power);
  s.emitterTree = LightTree(s.emitterTriangles, power);
  spdlog::debug("tsr::embree: scene {} v{} has {} emissive triangles", s.uid, s.version, power.size());
}
}  // namespace

void Scene::commit() {
  SceneState& s = *state_;
  const bool meshesChanged = !s.pending.meshes.empty();
  commitLevels(s);
  bool allViews = s.pending.materials && refreshMaterials(s);
  // A textured interior's views hold their mesh's bounds and depend on
  // whether their material is textured: refreshed on either edit.
  allViews = allViews || (s.texturedMedia && (s.pending.materials || meshesChanged));
  if (s.pending.lights) {
    s.activeLights.clear();
    for (const auto& l : s.lights)
      if (l) s.activeLights.push_back(*l);
  }
  refreshViews(s, allViews);
  if (s.pending.emitters) rebuildEmitters(s);
  s.pending = {};
}

void Scene::setTraceMemory(const TraceMemory& budget) {
  if (budget.bytes == 0 || budget.clusterTriangles == 0)
    throw Error("trace memory needs a budget and a cluster size above zero");
  if (budget == state_->traceMemory) return;
  state_->traceMemory = budget;
  state_->traceMemoryChanged = true;
}

TraceMemoryUse Scene::traceMemoryUse() const {
  TraceMemoryUse u = state_->streamed ? state_->streamed->use() : TraceMemoryUse{};
  u.wholeBytes = state_->mergedEstimate;
  return u;
}

std::uint64_t Scene::version() const { return state_->version; }
std::uint64_t Scene::appearanceVersion() const { return state_->appearance; }
std::uint64_t Scene::uid() const { return state_->uid; }

std::size_t Scene::instanceCount() const {
  std::size_t n = 0;
  for (const auto& i : state_->instances) n += i ? 1 : 0;
  return n;
}

bool Scene::bounds(glm::vec3& lo, glm::vec3& hi) const {
  lo = glm::vec3(std::numeric_limits<float>::max());
  hi = -lo;
  for (RTCScene level : {state_->traversable, state_->movingTraversable}) {
    if (!level) continue;
    RTCBounds b;
    rtcGetSceneBounds(level, &b);
    if (!(b.lower_x <= b.upper_x && b.lower_y <= b.upper_y && b.lower_z <= b.upper_z)) continue;  // empty level
    lo = glm::min(lo, glm::vec3(b.lower_x, b.lower_y, b.lower_z));
    hi = glm::max(hi, glm::vec3(b.upper_x, b.upper_y, b.upper_z));
  }
  return lo.x <= hi.x;
}

std::size_t Scene::meshCount() const {
  std::size_t n = 0;
  for (const auto& m : state_->meshes) n += m ? 1 : 0;
  return n;
}

RTCScene Scene::embreeScene() const { return state_->traversable ? state_->traversable : state_->top; }

}  // namespace tsr::embree
