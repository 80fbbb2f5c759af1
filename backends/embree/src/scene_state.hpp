#pragma once

#include "tsr/embree/distribution.hpp"
#include "tsr/embree/scene.hpp"

#include <embree3/rtcore.h>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include <limits>
#include <memory>
#include <optional>
#include <vector>

namespace tsr::embree {

// Internal representation shared by Scene (which edits it) and Renderer
// (which reads it after commit()).

struct MeshRecord {
  MeshData data;
  RTCScene scene = nullptr;
  RTCGeometry geometry = nullptr;
  std::uint32_t users = 0;  // instances referencing this mesh
  bool dirty = true;

  MeshRecord() = default;
  MeshRecord(const MeshRecord&) = delete;
  MeshRecord& operator=(const MeshRecord&) = delete;
  ~MeshRecord() {
    if (geometry) rtcReleaseGeometry(geometry);
    if (scene) rtcReleaseScene(scene);
  }
};

struct InstanceRecord {
  MeshId mesh{};
  MaterialId material{};
  glm::mat4 transform{1.0f};
  RTCGeometry geometry = nullptr;
  bool dirty = true;

  InstanceRecord() = default;
  InstanceRecord(const InstanceRecord&) = delete;
  InstanceRecord& operator=(const InstanceRecord&) = delete;
  ~InstanceRecord() {
    if (geometry) rtcReleaseGeometry(geometry);
  }
};

struct ResolvedMaterial {
  Material material;
  const Texture* baseColorTexture = nullptr;
  const Texture* emissionTexture = nullptr;
};

inline constexpr std::uint32_t kNotEmissive = std::numeric_limits<std::uint32_t>::max();

// Flattened, render-ready view of one instance, indexed by instance id.
struct InstanceView {
  const MeshData* mesh = nullptr;
  glm::mat4 transform{1.0f};
  glm::mat3 normalTransform{1.0f};
  const ResolvedMaterial* material = nullptr;
  std::uint32_t emissiveOffset = kNotEmissive;  // first triangle in the emitter distribution
};

struct EmissiveRange {
  std::uint32_t offset;
  std::uint32_t instance;
};

struct SceneState {
  std::shared_ptr<Device> device;
  RTCScene top = nullptr;
  std::uint64_t uid = 0;
  std::uint64_t version = 1;

  std::vector<std::unique_ptr<MeshRecord>> meshes;
  std::vector<std::unique_ptr<InstanceRecord>> instances;
  std::vector<std::optional<Material>> materials;
  std::vector<std::shared_ptr<const Texture>> textures;
  std::vector<std::optional<Light>> lights;
  Environment environment;

  bool topDirty = true;
  bool derivedDirty = true;

  // Derived at commit().
  std::vector<ResolvedMaterial> resolved;
  std::vector<InstanceView> views;
  std::vector<Light> activeLights;
  Distribution1D emitters;
  std::vector<EmissiveRange> emissiveRanges;
};

}  // namespace tsr::embree
