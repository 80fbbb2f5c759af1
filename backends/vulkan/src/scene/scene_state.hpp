#pragma once

#include "gpu_types.hpp"
#include "lights/emitter_lights.hpp"
#include "resources/buffer.hpp"
#include "resources/image.hpp"
#include "scene/geometry_arena.hpp"

#include "tsr/vk/device.hpp"
#include "tsr/vk/environment.hpp"
#include "tsr/vk/material.hpp"
#include "tsr/vk/mesh.hpp"
#include "tsr/vk/vocabulary.hpp"

#include <glm/vec3.hpp>

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace tsr::vk {

// A mesh: its place in the geometry arena and what is known about it.
struct MeshRecord {
  GeometrySpan span;
  std::uint32_t vertexCount = 0;
  std::uint32_t indexCount = 0;
  Primitive primitive = Primitive::Triangles;
  std::vector<EmitterPatch> patches;  // made when an emissive instance first uses the mesh
  bool patchesDirty = true;
  float area = 0.0f;  // surface area, for the emitters' ambient term (none for lines and points)
  glm::vec3 boundsMin{0.0f};
  glm::vec3 boundsMax{0.0f};
  std::uint32_t users = 0;
  bool alive = false;
};

// Where a mesh's indices start in its block's index buffer.
inline std::uint32_t firstIndexOf(const MeshRecord& m) { return m.span.firstIndex; }
// What draws add to the mesh's indices.
inline std::int32_t vertexOffsetOf(const MeshRecord& m) { return std::int32_t(m.span.baseVertex); }

struct InstanceRecord {
  std::uint32_t mesh = 0;
  std::uint32_t material = 0;
  glm::mat4 transform{1.0f};
  bool alive = false;
  std::uint32_t object = 0;  // what the id pass writes
};

struct MaterialRecord {
  Material material;
  VkDescriptorSet set = VK_NULL_HANDLE;  // textures, set = 1
  VkDescriptorPool pool = VK_NULL_HANDLE;
  std::uint32_t users = 0;
  bool alive = false;
};

struct TextureRecord {
  Image image;
  std::uint32_t users = 0;
  bool alive = false;
};

struct LightRecord {
  Light light;
  bool alive = false;
};

// Instances that share mesh and material, drawn with one instanced call whose
// gl_InstanceIndex runs over drawOrder[first, first + count).
struct DrawGroup {
  std::uint32_t mesh = 0;
  std::uint32_t material = 0;
  std::uint32_t first = 0;
  std::uint32_t count = 0;
};

// Material textures in set 1: base colour, emission, metallic-roughness, normal.
inline constexpr std::uint32_t kMaterialTextures = std::uint32_t(kTextureSlots);

// The set-1 layout for material textures. Scene and Renderer each create one
// with this function; identically defined layouts are compatible.
VkDescriptorSetLayout createMaterialSetLayout(VkDevice device);

struct SceneState {
  std::shared_ptr<Device> device;
  // Unique in the process: a renderer tells a scene made at a freed one's
  // address from that one (what its shadow maps hold).
  const std::uint64_t uid = nextUid();
  std::uint64_t version = 0;
  // Edits that change what casts shadows beyond single instances (a mesh's
  // vertices or removal, a material): the shadow maps are drawn whole
  // after one (lights/shadow_update.hpp).
  std::uint64_t casterEdits = 0;

  std::optional<GeometryArena> geometry;  // made with the scene
  std::vector<MeshRecord> meshes;
  std::vector<InstanceRecord> instances;
  std::vector<MaterialRecord> materials;
  std::vector<TextureRecord> textures;
  std::vector<LightRecord> lights;
  Environment environment;

  Buffer instanceBuffer;  // GpuInstance per instance slot, host-visible
  Buffer materialBuffer;  // GpuMaterial per material slot, host-visible
  Buffer objectBuffer;    // uint32 object id per instance slot, host-visible (id pass)
  bool materialsDirty = true;

  VkDescriptorSetLayout materialSetLayout = VK_NULL_HANDLE;
  std::vector<VkDescriptorPool> materialPools;
  VkSampler sampler = VK_NULL_HANDLE;
  Image whiteTexture;
  Image environmentMap;  // Environment::prefiltered(), uploaded by setEnvironment

  // Derived for drawing; rebuilt by prepare() when drawListDirty.
  bool drawListDirty = true;
  std::vector<DrawGroup> opaqueGroups;
  std::vector<std::uint32_t> opaqueOrder;
  std::vector<std::uint32_t> transparent;  // instance slots, unsorted
  // Instances of line and point meshes, grouped like the opaque ones: drawn
  // unlit after them, never culled, casting no shadow.
  std::vector<DrawGroup> lineGroups;
  std::vector<std::uint32_t> lineOrder;
  bool boundsDirty = true;
  // Bounds of the surfaces (lines and points left out), and whether any.
  glm::vec3 sceneMin{0.0f};
  glm::vec3 sceneMax{0.0f};
  bool sceneEmpty = true;

  std::uint64_t geometryBytes = 0;
  std::uint64_t instanceBytes = 0;

  // Brings the material buffer, draw groups and bounds up to date.
  void prepare();
  // World-space bounds of one instance.
  void instanceBounds(std::uint32_t slot, glm::vec3& lo, glm::vec3& hi) const;

 private:
  static std::uint64_t nextUid() {
    static std::atomic<std::uint64_t> next{1};
    return next.fetch_add(1, std::memory_order_relaxed);
  }
};

}  // namespace tsr::vk
