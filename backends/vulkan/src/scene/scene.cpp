#include "tsr/vk/scene.hpp"

#include "scene/scene_state.hpp"

#include "tsr/backend/validate.hpp"
#include "tsr/vk/error.hpp"
#include "vk_struct.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>

namespace tsr::vk {

namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finiteNonNegative(const glm::vec3& v) { return finite(v) && v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f; }

bool finite(const glm::mat4& m) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (!std::isfinite(m[i][j])) return false;
  return true;
}

template <class Record>
Record& lookup(std::vector<Record>& records, std::uint32_t i, const char* what) {
  if (i >= records.size() || !records[i].alive)
    throw Error(std::string("unknown ") + what + " id " + std::to_string(i));
  return records[i];
}

GpuInstance makeInstance(const glm::mat4& m, const GeometrySpan& mesh) {
  // Cofactor matrix = det * inverse transpose: well defined even for a
  // degenerate scale; the sign of det keeps the inverse transpose's direction.
  const glm::vec3 c0(m[0]), c1(m[1]), c2(m[2]);
  const float det = glm::dot(c0, glm::cross(c1, c2));
  const float s = det < 0.0f ? -1.0f : 1.0f;
  GpuInstance g;
  g.model = m;
  g.positionOffset = glm::vec4(mesh.quantization.lo, 0.0f);
  g.positionScale = glm::vec4(mesh.quantization.scale(), mesh.uvDensity);
  g.uvBox = glm::vec4(mesh.uvQuantization.lo, mesh.uvQuantization.scale());
  g.normal = glm::mat4(glm::vec4(s * glm::cross(c1, c2), 0.0f), glm::vec4(s * glm::cross(c2, c0), 0.0f),
                       glm::vec4(s * glm::cross(c0, c1), 0.0f), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  return g;
}

VkFormat textureFormat(TextureFormat f) {
  switch (f) {
    case TextureFormat::Rgba8Srgb:
      return VK_FORMAT_R8G8B8A8_SRGB;
    case TextureFormat::Rgba8Unorm:
      return VK_FORMAT_R8G8B8A8_UNORM;
    case TextureFormat::Rgba32F:
      return VK_FORMAT_R32G32B32A32_SFLOAT;
  }
  throw Error("unknown texture format");
}

// The prefiltered radiance, one upload per environment.
void uploadEnvironment(SceneState& s) {
  const auto& texels = s.environment.prefiltered();
  s.environmentMap = uploadImage(*s.device, Environment::kWidth, Environment::kHeight * Environment::kLevels,
                                 VK_FORMAT_R32G32B32A32_SFLOAT, texels.data(), texels.size() * sizeof(glm::vec4));
}

void validateMaterial(const Material& m, const SceneState& s) {
  if (!finiteNonNegative(m.baseColor)) throw Error("material baseColor must be finite and non-negative");
  if (!finiteNonNegative(m.emission)) throw Error("material emission must be finite and non-negative");
  if (!(m.roughness >= 0.0f && m.roughness <= 1.0f)) throw Error("material roughness must be in [0, 1]");
  if (!(m.ior > 0.0f) || !std::isfinite(m.ior)) throw Error("material ior must be positive and finite");
  if (!(m.opacity >= 0.0f && m.opacity <= 1.0f)) throw Error("material opacity must be in [0, 1]");
  if (!(m.alphaCutoff >= 0.0f && m.alphaCutoff <= 1.0f)) throw Error("material alphaCutoff must be in [0, 1]");
  if (m.interior) {
    const Medium& v = *m.interior;
    if (!finiteNonNegative(v.absorption) || !finiteNonNegative(v.scattering) || !finiteNonNegative(v.emission))
      throw Error("material interior coefficients must be finite and non-negative");
    if (!(std::abs(v.g) < 1.0f)) throw Error("material interior phase g must be in (-1, 1)");
  }
  if (!(m.metallic >= 0.0f && m.metallic <= 1.0f)) throw Error("material metallic must be in [0, 1]");
  if (!std::isfinite(m.normalScale)) throw Error("material normalScale must be finite");
  if (!(std::isfinite(m.occlusionStrength) && m.occlusionStrength >= 0.0f && m.occlusionStrength <= 1.0f))
    throw Error("material occlusionStrength must be in [0, 1]");
  for (const UvTransform& t : m.uv)
    for (int i = 0; i < 3; ++i)
      if (!std::isfinite(t.row0[i]) || !std::isfinite(t.row1[i])) throw Error("material uv transforms must be finite");
  for (const auto& t : m.textures()) {
    if (t && (index(*t) >= s.textures.size() || !s.textures[index(*t)].alive))
      throw Error("material refers to unknown texture id " + std::to_string(index(*t)));
  }
}

void validateLight(const Light& light) {
  std::visit(
      [](const auto& l) {
        using T = std::decay_t<decltype(l)>;
        if constexpr (std::is_same_v<T, PointLight>) {
          if (!finite(l.position)) throw Error("point light position must be finite");
          if (!finiteNonNegative(l.intensity)) throw Error("point light intensity must be finite and non-negative");
        } else if constexpr (std::is_same_v<T, SpotLight>) {
          if (!finite(l.position) || !finite(l.direction)) throw Error("spot light position/direction must be finite");
          if (!finiteNonNegative(l.intensity)) throw Error("spot light intensity must be finite and non-negative");
          if (!(glm::length(l.direction) > 0.0f)) throw Error("spot light direction is zero");
          if (!(l.innerAngle >= 0.0f && l.innerAngle <= l.outerAngle && l.outerAngle < 3.14159f))
            throw Error("spot light angles must satisfy 0 <= inner <= outer < pi");
        } else {
          if (!finite(l.direction) || !(glm::length(l.direction) > 0.0f))
            throw Error("directional light direction must be finite and non-zero");
          if (!finiteNonNegative(l.irradiance))
            throw Error("directional light irradiance must be finite and non-negative");
        }
      },
      light);
}

void ensureHostCapacity(const Device& device, Buffer& buffer, VkDeviceSize needed, VkBufferUsageFlags usage) {
  if (buffer && buffer.size() >= needed) return;
  const VkDeviceSize size = std::max<VkDeviceSize>({needed, buffer ? 2 * buffer.size() : 0, 4096});
  Buffer grown(device, size, usage, Buffer::kHost);
  if (buffer) std::memcpy(grown.mapped(), buffer.mapped(), buffer.size());
  buffer = std::move(grown);
}

}  // namespace

VkDescriptorSetLayout createMaterialSetLayout(VkDevice device) {
  VkDescriptorSetLayoutBinding bindings[kMaterialTextures]{};
  for (std::uint32_t i = 0; i < kMaterialTextures; ++i) {
    bindings[i].binding = i;
    bindings[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    bindings[i].descriptorCount = 1;
    bindings[i].stageFlags = VK_SHADER_STAGE_FRAGMENT_BIT;
  }
  VkDescriptorSetLayoutCreateInfo ci =
      vkStruct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
  ci.bindingCount = kMaterialTextures;
  ci.pBindings = bindings;
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  check(vkCreateDescriptorSetLayout(device, &ci, nullptr, &layout), "vkCreateDescriptorSetLayout (material)");
  return layout;
}

void SceneState::instanceBounds(std::uint32_t slot, glm::vec3& lo, glm::vec3& hi) const {
  const InstanceRecord& inst = instances[slot];
  const MeshRecord& mesh = meshes[inst.mesh];
  lo = glm::vec3(std::numeric_limits<float>::infinity());
  hi = -lo;
  for (int c = 0; c < 8; ++c) {
    glm::vec3 p((c & 1) ? mesh.boundsMax.x : mesh.boundsMin.x, (c & 2) ? mesh.boundsMax.y : mesh.boundsMin.y,
                (c & 4) ? mesh.boundsMax.z : mesh.boundsMin.z);
    glm::vec3 w(inst.transform * glm::vec4(p, 1.0f));
    lo = glm::min(lo, w);
    hi = glm::max(hi, w);
  }
}

void SceneState::prepare() {
  if (materialsDirty) {
    ensureHostCapacity(*device, materialBuffer, std::max<std::size_t>(materials.size(), 1) * sizeof(GpuMaterial),
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    auto* out = static_cast<GpuMaterial*>(materialBuffer.mapped());
    for (std::size_t i = 0; i < materials.size(); ++i) {
      const Material& m = materials[i].material;
      GpuMaterial g{};
      g.baseColor = glm::vec4(m.baseColor, m.opacity);
      g.emission = glm::vec4(m.emission, 0.0f);
      g.params = glm::vec4(std::max(1e-3f, m.roughness * m.roughness), m.ior, m.occlusionStrength, 0.0f);
      for (std::size_t t = 0; t < kTextureSlots; ++t) {
        g.uv[2 * t] = glm::vec4(m.uv[t].row0, 0.0f);
        g.uv[2 * t + 1] = glm::vec4(m.uv[t].row1, 0.0f);
      }
      g.pbr = glm::vec4(m.roughness, m.metallic, m.normalScale, m.alphaCutoff);
      if (m.interior) {
        g.mediumAbsorption = glm::vec4(m.interior->absorption, std::clamp(m.interior->g, -0.99f, 0.99f));
        g.mediumScattering = glm::vec4(m.interior->scattering, 0.0f);
        g.mediumEmission = glm::vec4(m.interior->emission, 0.0f);
      }
      out[i] = g;
    }
    materialsDirty = false;
  }
  if (drawListDirty) {
    std::vector<std::uint32_t> opaque, lines;
    transparent.clear();
    for (std::uint32_t i = 0; i < instances.size(); ++i) {
      if (!instances[i].alive) continue;
      if (meshes[instances[i].mesh].primitive != Primitive::Triangles)
        lines.push_back(i);
      else
        (materials[instances[i].material].material.isTransparent() ? transparent : opaque).push_back(i);
    }
    // Material first: runs of one material over one geometry block draw without new bindings.
    auto grouped = [this](std::vector<std::uint32_t> order, std::vector<DrawGroup>& groups) {
      std::sort(order.begin(), order.end(), [this](std::uint32_t a, std::uint32_t b) {
        const InstanceRecord& x = instances[a];
        const InstanceRecord& y = instances[b];
        if (x.material != y.material) return x.material < y.material;
        if (x.mesh != y.mesh) return x.mesh < y.mesh;
        return a < b;
      });
      groups.clear();
      for (std::uint32_t i = 0; i < order.size(); ++i) {
        const InstanceRecord& r = instances[order[i]];
        if (groups.empty() || groups.back().mesh != r.mesh || groups.back().material != r.material)
          groups.push_back({r.mesh, r.material, i, 0});
        ++groups.back().count;
      }
      return order;
    };
    opaqueOrder = grouped(std::move(opaque), opaqueGroups);
    lineOrder = grouped(std::move(lines), lineGroups);
    drawListDirty = false;
  }
  if (boundsDirty) {
    sceneMin = glm::vec3(std::numeric_limits<float>::infinity());
    sceneMax = -sceneMin;
    sceneEmpty = true;
    for (std::uint32_t i = 0; i < instances.size(); ++i) {
      // Surfaces only: the bounds fit the shadow maps and the probe, which
      // lines and points take no part in (a large grid would blur them).
      if (!instances[i].alive || meshes[instances[i].mesh].primitive != Primitive::Triangles) continue;
      glm::vec3 lo, hi;
      instanceBounds(i, lo, hi);
      sceneMin = glm::min(sceneMin, lo);
      sceneMax = glm::max(sceneMax, hi);
      sceneEmpty = false;
    }
    boundsDirty = false;
  }
}

Scene::Scene(std::shared_ptr<Device> device) : state_(std::make_unique<SceneState>()) {
  if (!device) throw Error("scene needs a device");
  SceneState& s = *state_;
  s.device = std::move(device);
  VkDevice dev = s.device->handle();
  s.materialSetLayout = createMaterialSetLayout(dev);
  s.geometry.emplace(*s.device);

  VkSamplerCreateInfo sci = vkStruct<VkSamplerCreateInfo>(VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO);
  sci.magFilter = VK_FILTER_LINEAR;
  sci.minFilter = VK_FILTER_LINEAR;
  // Trilinear over the textures' mip chains (images of one level sample it alone).
  sci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  sci.maxLod = VK_LOD_CLAMP_NONE;
  check(vkCreateSampler(dev, &sci, nullptr, &s.sampler), "vkCreateSampler");

  const std::uint8_t white[4] = {255, 255, 255, 255};
  s.whiteTexture = uploadImage(*s.device, 1, 1, VK_FORMAT_R8G8B8A8_UNORM, white, 4);
  uploadEnvironment(s);
  ensureHostCapacity(*s.device, s.instanceBuffer, 64 * sizeof(GpuInstance), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
}

Scene::~Scene() {
  SceneState& s = *state_;
  VkDevice dev = s.device->handle();
  vkDeviceWaitIdle(dev);
  for (VkDescriptorPool p : s.materialPools) vkDestroyDescriptorPool(dev, p, nullptr);
  if (s.sampler) vkDestroySampler(dev, s.sampler, nullptr);
  if (s.materialSetLayout) vkDestroyDescriptorSetLayout(dev, s.materialSetLayout, nullptr);
}

const Device& Scene::device() const { return *state_->device; }
std::uint64_t Scene::version() const { return state_->version; }
std::uint64_t Scene::geometryBytesUploaded() const { return state_->geometryBytes; }
std::uint64_t Scene::geometryBytesHeld() const { return state_->geometry->bytesAllocated(); }
std::uint64_t Scene::instanceBytesWritten() const { return state_->instanceBytes; }

std::size_t Scene::instanceCount() const {
  return std::count_if(state_->instances.begin(), state_->instances.end(), [](const auto& r) { return r.alive; });
}
std::size_t Scene::meshCount() const {
  return std::count_if(state_->meshes.begin(), state_->meshes.end(), [](const auto& r) { return r.alive; });
}

MeshId Scene::addMesh(const MeshData& data) {
  SceneState& s = *state_;
  const std::size_t n = data.positions.size();
  if (n == 0) throw Error("mesh has no positions");
  if (n > std::numeric_limits<std::uint32_t>::max()) throw Error("mesh has too many vertices");
  const std::size_t per = indicesPer(data.primitive);
  if (data.indices.empty() || data.indices.size() % per != 0)
    throw Error("mesh index count must be a non-zero multiple of " + std::to_string(per) + ", got " +
                std::to_string(data.indices.size()));
  if (!data.normals.empty() && data.normals.size() != n)
    throw Error("mesh has " + std::to_string(data.normals.size()) + " normals for " + std::to_string(n) + " positions");
  if (!data.uvs.empty() && data.uvs.size() != n)
    throw Error("mesh has " + std::to_string(data.uvs.size()) + " uvs for " + std::to_string(n) + " positions");
  for (std::size_t i = 0; i < data.indices.size(); ++i)
    if (data.indices[i] >= n)
      throw Error("mesh index " + std::to_string(i) + " = " + std::to_string(data.indices[i]) + " is out of range (" +
                  std::to_string(n) + " vertices)");
  for (const auto& p : data.positions)
    if (!finite(p)) throw Error("mesh positions contain NaN or infinity");
  for (const auto& v : data.normals)
    if (!finite(v)) throw Error("mesh normals contain NaN or infinity");
  for (const auto& uv : data.uvs)
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) throw Error("mesh uvs contain NaN or infinity");

  MeshRecord m;
  m.vertexCount = std::uint32_t(n);
  m.indexCount = std::uint32_t(data.indices.size());
  m.primitive = data.primitive;
  m.span = s.geometry->add(data);
  s.geometryBytes += n * s.geometry->vertexBytes() + data.indices.size() * (n > (1u << 16) ? 4 : 2);
  if (m.primitive == Primitive::Triangles) m.area = meshArea(data.positions, data.indices);
  // The arena's quantization box is the positions' bounds: not walked twice.
  m.boundsMin = m.span.quantization.lo;
  m.boundsMax = m.span.quantization.hi;
  m.alive = true;
  s.meshes.push_back(std::move(m));
  ++s.version;
  return MeshId(std::uint32_t(s.meshes.size() - 1));
}

void Scene::updateMeshVertices(MeshId mesh, const VertexEdit& edit) {
  SceneState& s = *state_;
  MeshRecord& m = lookup(s.meshes, index(mesh), "mesh");
  backend::validate<Error>(edit, m.vertexCount);
  if (edit.count == 0) return;
  for (const auto& p : edit.changedPositions())
    if (!finite(p)) throw Error("updated positions contain NaN or infinity");
  for (const auto& v : edit.changedNormals())
    if (!finite(v)) throw Error("updated normals contain NaN or infinity");

  const bool requantized = s.geometry->updateVertices(m.span, edit);
  s.geometryBytes += (requantized ? m.vertexCount : edit.count) * s.geometry->positionBytes() +
                     edit.changedNormals().size() * sizeof(OctNormal);
  if (requantized) {
    // The mesh's box changed: its instances decode positions by the new one.
    auto* gpu = static_cast<GpuInstance*>(s.instanceBuffer.mapped());
    for (std::uint32_t slot = 0; slot < s.instances.size(); ++slot)
      if (s.instances[slot].alive && s.instances[slot].mesh == index(mesh)) {
        gpu[slot] = makeInstance(s.instances[slot].transform, m.span);
        s.instanceBytes += sizeof(GpuInstance);
      }
  }
  m.patchesDirty = true;
  // Bounds are the box (the exact bounds of the edit's positions); the area
  // is taken from those exact positions and the arena's indices.
  if (m.primitive == Primitive::Triangles) m.area = meshArea(edit.positions, s.geometry->indices(m.span, m.indexCount));
  m.boundsMin = m.span.quantization.lo;
  m.boundsMax = m.span.quantization.hi;
  s.boundsDirty = true;
  ++s.casterEdits;
  ++s.version;
}

void Scene::removeMesh(MeshId mesh) {
  SceneState& s = *state_;
  MeshRecord& m = lookup(s.meshes, index(mesh), "mesh");
  if (m.users > 0) throw Error("mesh " + std::to_string(index(mesh)) + " is still used by instances");
  s.geometry->release(m.span);
  m = MeshRecord{};
  ++s.casterEdits;
  ++s.version;
}

InstanceId Scene::addInstance(MeshId mesh, MaterialId material, const glm::mat4& transform) {
  SceneState& s = *state_;
  MeshRecord& m = lookup(s.meshes, index(mesh), "mesh");
  MaterialRecord& mat = lookup(s.materials, index(material), "material");
  if (!finite(transform)) throw Error("instance transform contains NaN or infinity");
  const std::uint32_t slot = std::uint32_t(s.instances.size());
  ensureHostCapacity(*s.device, s.instanceBuffer, (slot + 1) * sizeof(GpuInstance), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  ensureHostCapacity(*s.device, s.objectBuffer, (slot + 1) * sizeof(std::uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  s.instances.push_back({index(mesh), index(material), transform, true, slot + 1});
  static_cast<GpuInstance*>(s.instanceBuffer.mapped())[slot] = makeInstance(transform, m.span);
  static_cast<std::uint32_t*>(s.objectBuffer.mapped())[slot] = slot + 1;
  s.instanceBytes += sizeof(GpuInstance);
  ++m.users;
  ++mat.users;
  s.drawListDirty = s.boundsDirty = true;
  ++s.version;
  return InstanceId(slot);
}

void Scene::setInstanceTransform(InstanceId instance, const glm::mat4& transform) {
  SceneState& s = *state_;
  InstanceRecord& r = lookup(s.instances, index(instance), "instance");
  if (!finite(transform)) throw Error("instance transform contains NaN or infinity");
  r.transform = transform;
  static_cast<GpuInstance*>(s.instanceBuffer.mapped())[index(instance)] =
      makeInstance(transform, s.meshes[r.mesh].span);
  s.instanceBytes += sizeof(GpuInstance);
  s.boundsDirty = true;
  ++s.version;
}

void Scene::setInstanceObject(InstanceId instance, std::uint32_t object) {
  SceneState& s = *state_;
  InstanceRecord& r = lookup(s.instances, index(instance), "instance");
  r.object = object;
  static_cast<std::uint32_t*>(s.objectBuffer.mapped())[index(instance)] = object;
  ++s.version;
}

std::uint32_t Scene::instanceObject(InstanceId instance) const {
  return lookup(state_->instances, index(instance), "instance").object;
}

void Scene::setInstanceMaterial(InstanceId instance, MaterialId material) {
  SceneState& s = *state_;
  InstanceRecord& r = lookup(s.instances, index(instance), "instance");
  MaterialRecord& mat = lookup(s.materials, index(material), "material");
  --s.materials[r.material].users;
  ++mat.users;
  r.material = index(material);
  s.drawListDirty = true;
  ++s.version;
}

void Scene::removeInstance(InstanceId instance) {
  SceneState& s = *state_;
  InstanceRecord& r = lookup(s.instances, index(instance), "instance");
  --s.meshes[r.mesh].users;
  --s.materials[r.material].users;
  r.alive = false;
  s.drawListDirty = s.boundsDirty = true;
  ++s.version;
}

namespace {
void writeMaterialSet(SceneState& s, MaterialRecord& r) {
  VkDescriptorImageInfo images[kMaterialTextures];
  const auto ids = r.material.textures();
  for (std::uint32_t i = 0; i < kMaterialTextures; ++i) {
    images[i].sampler = s.sampler;
    images[i].imageView = ids[i] ? s.textures[index(*ids[i])].image.view() : s.whiteTexture.view();
    images[i].imageLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  }
  VkWriteDescriptorSet w = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
  w.dstSet = r.set;
  w.dstBinding = 0;
  w.descriptorCount = kMaterialTextures;
  w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  w.pImageInfo = images;
  vkUpdateDescriptorSets(s.device->handle(), 1, &w, 0, nullptr);
}

void retainTextures(SceneState& s, const Material& m, int delta) {
  for (const auto& t : m.textures())
    if (t) s.textures[index(*t)].users += delta;
}

void allocateMaterialSet(SceneState& s, MaterialRecord& r) {
  VkDevice dev = s.device->handle();
  VkDescriptorSetAllocateInfo ai =
      vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &s.materialSetLayout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  if (!s.materialPools.empty()) {
    ai.descriptorPool = s.materialPools.back();
    VkResult res = vkAllocateDescriptorSets(dev, &ai, &set);
    if (res == VK_SUCCESS) {
      r.set = set;
      r.pool = ai.descriptorPool;
      return;
    }
    if (res != VK_ERROR_OUT_OF_POOL_MEMORY && res != VK_ERROR_FRAGMENTED_POOL) check(res, "vkAllocateDescriptorSets");
  }
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kMaterialTextures * 256};
  VkDescriptorPoolCreateInfo pci = vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
  pci.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pci.maxSets = 256;
  pci.poolSizeCount = 1;
  pci.pPoolSizes = &size;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  check(vkCreateDescriptorPool(dev, &pci, nullptr, &pool), "vkCreateDescriptorPool");
  s.materialPools.push_back(pool);
  ai.descriptorPool = pool;
  check(vkAllocateDescriptorSets(dev, &ai, &set), "vkAllocateDescriptorSets");
  r.set = set;
  r.pool = pool;
}
}  // namespace

MaterialId Scene::addMaterial(const Material& material) {
  SceneState& s = *state_;
  validateMaterial(material, s);
  MaterialRecord r;
  r.material = material;
  allocateMaterialSet(s, r);
  r.alive = true;
  writeMaterialSet(s, r);
  retainTextures(s, material, +1);
  s.materials.push_back(r);
  s.materialsDirty = true;
  ++s.version;
  return MaterialId(std::uint32_t(s.materials.size() - 1));
}

void Scene::setMaterial(MaterialId id, const Material& material) {
  SceneState& s = *state_;
  MaterialRecord& r = lookup(s.materials, index(id), "material");
  validateMaterial(material, s);
  if (r.material.isTransparent() != material.isTransparent()) s.drawListDirty = true;
  retainTextures(s, material, +1);
  retainTextures(s, r.material, -1);
  r.material = material;
  writeMaterialSet(s, r);
  s.materialsDirty = true;
  ++s.casterEdits;
  ++s.version;
}

void Scene::removeMaterial(MaterialId id) {
  SceneState& s = *state_;
  MaterialRecord& r = lookup(s.materials, index(id), "material");
  if (r.users > 0) throw Error("material " + std::to_string(index(id)) + " is still used by instances");
  retainTextures(s, r.material, -1);
  check(vkFreeDescriptorSets(s.device->handle(), r.pool, 1, &r.set), "vkFreeDescriptorSets");
  r.alive = false;
  r.set = VK_NULL_HANDLE;
  s.materialsDirty = true;
  ++s.version;
}

TextureId Scene::addTexture(const Texture& texture) {
  SceneState& s = *state_;
  TextureRecord r;
  r.image = uploadImage(*s.device, texture.width(), texture.height(), textureFormat(texture.format()),
                        texture.bytes().data(), texture.bytes().size(), /*mipmapped=*/true);
  r.alive = true;
  s.textures.push_back(std::move(r));
  ++s.version;
  return TextureId(std::uint32_t(s.textures.size() - 1));
}

void Scene::removeTexture(TextureId id) {
  SceneState& s = *state_;
  TextureRecord& r = lookup(s.textures, index(id), "texture");
  if (r.users > 0) throw Error("texture " + std::to_string(index(id)) + " is still used by materials");
  r = TextureRecord{};
  ++s.version;
}

LightId Scene::addLight(const Light& light) {
  SceneState& s = *state_;
  validateLight(light);
  s.lights.push_back({light, true});
  ++s.version;
  return LightId(std::uint32_t(s.lights.size() - 1));
}

void Scene::setLight(LightId id, const Light& light) {
  SceneState& s = *state_;
  LightRecord& r = lookup(s.lights, index(id), "light");
  validateLight(light);
  r.light = light;
  ++s.version;
}

void Scene::removeLight(LightId id) {
  SceneState& s = *state_;
  lookup(s.lights, index(id), "light").alive = false;
  ++s.version;
}

void Scene::setEnvironment(const Environment& environment) {
  state_->environment = environment;
  uploadEnvironment(*state_);
  ++state_->version;
}

}  // namespace tsr::vk
