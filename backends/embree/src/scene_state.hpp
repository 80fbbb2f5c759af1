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
  bool dirty = true;         // data changed since the last commit
  bool sceneStale = true;    // its own BVH not built for the current data

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
  RTCGeometry geometry = nullptr;      // the instance in the top level
  RTCGeometry flatGeometry = nullptr;  // or its triangles in world space, in the merged scene
  bool flat = false;
  bool dirty = true;

  InstanceRecord() = default;
  InstanceRecord(const InstanceRecord&) = delete;
  InstanceRecord& operator=(const InstanceRecord&) = delete;
  ~InstanceRecord() {
    if (geometry) rtcReleaseGeometry(geometry);
    if (flatGeometry) rtcReleaseGeometry(flatGeometry);
  }
};

// Ids in the top-level scene: the merged static scene is instanced at 0,
// instance i at i + 1. In the merged scene, instance i's triangles have
// geometry id i.
inline constexpr std::uint32_t kMergedTopId = 0;
inline std::uint32_t topId(std::uint32_t instance) { return instance + 1; }

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
  glm::mat3 normalTransform{1.0f};  // inverse transpose, for shading normals
  // Cofactor matrix (det * inverse transpose): takes an object-space face
  // normal to world space keeping the winding's orientation under mirroring.
  glm::mat3 faceNormalTransform{1.0f};
  const ResolvedMaterial* material = nullptr;
  std::uint32_t emissiveOffset = kNotEmissive;  // first triangle in the emitter distribution
};

// An emissive triangle in world space, prepared at commit for light sampling.
struct EmitterTriangle {
  glm::vec3 p0, e1, e2;  // vertex 0 and the edges to vertices 1 and 2
  glm::vec3 normal;      // unit face normal, from the winding
  float area;
};

struct EmissiveRange {
  std::uint32_t offset;
  std::uint32_t instance;
};

struct SceneState {
  std::shared_ptr<Device> device;
  RTCScene top = nullptr;
  // Static meshes used by exactly one instance are merged, in world space,
  // into one high-quality acceleration structure: no instance traversal and
  // one BVH over interleaved objects. Shared or animated meshes stay instanced.
  RTCScene merged = nullptr;
  RTCGeometry mergedInstance = nullptr;
  bool mergedDirty = true;
  // What rays traverse, set at commit: the merged scene itself when nothing
  // is instanced (no top level to cross), else the top level.
  RTCScene traversable = nullptr;
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
  std::vector<EmitterTriangle> emitterTriangles;  // indexed like emitters
  std::vector<EmissiveRange> emissiveRanges;
};

}  // namespace tsr::embree
