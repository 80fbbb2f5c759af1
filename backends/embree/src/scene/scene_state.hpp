#pragma once

#include "scene/instance_motion.hpp"
#include "scene/light_tree.hpp"
#include "scene/volume_field.hpp"
#include "tsr/backend/embree_triangles.hpp"
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

class StreamedGeometry;

// Internal representation shared by Scene (which edits it) and Renderer
// (which reads it after commit()).

// Its scene and geometry (EmbreeTriangles) are released with it. The scene
// exists from the start (instances point at it); its geometry, Embree's
// copy of the triangles, and its BVH are made only when an instance
// traverses the mesh through the top or moving level (fill): a mesh whose
// one instance is copied into the merged scene never holds them (every leaf
// of a generated plant; 26 bytes a triangle).
struct MeshRecord : backend::EmbreeTriangles {
  MeshData data;
  std::vector<std::uint32_t> users;  // ids of the instances referencing this mesh
  bool dirty = false;                // data changed since the last commit (listed in Pending)
  bool sceneStale = true;            // its own BVH not built for the current data
  // Bounds that every level holding an instance of this mesh was built with
  // (or around): a ray reaches the mesh's own BVH through the instance at
  // trace time, so a vertex edit that keeps the mesh inside them rebuilds
  // that BVH alone and touches no instance and no level.
  RTCBounds levelBounds{};
  bool shrunk = false;  // inside levelBounds but smaller: listed in SceneState::shrunkMeshes

  bool filled() const { return geometry != nullptr; }
  // Embree's copy of `data` (again); throws Error when Embree cannot allocate it.
  void fill(RTCDevice device);
};

// Where an instance's triangles are traced from.
enum class Level : std::uint8_t {
  None,    // not placed yet
  Merged,  // copied to world space into the merged static scene
  Top,     // instanced in the top level, which rarely changes
  Moving,  // instanced in the small moving level only: its mesh changed since it was added
  // Moved from the top level without rebuilding it: its current copy is in
  // the moving level, its old copy stays in the top level as a ghost whose
  // hits the tracer rejects, until the top level rebuilds.
  Ghosted,
};

struct InstanceRecord {
  MeshId mesh{};
  MaterialId material{};
  glm::mat4 transform{1.0f};
  // Moving over the frame interval (null: still): traced in the moving
  // level with two time steps.
  std::unique_ptr<InstanceMotion> motion;
  RTCGeometry geometry = nullptr;        // the instance in the top level (Top, or a ghost while Ghosted)
  RTCGeometry movingGeometry = nullptr;  // the instance in the moving level (Moving, Ghosted)
  RTCGeometry flatGeometry = nullptr;    // or its triangles in world space, in the merged scene
  Level level = Level::None;
  std::uint32_t movingId = 0;  // its id in the moving level, while there
  bool moved = false;          // transform or mesh edited since it was placed: it belongs to the moving level
  bool meshChanged = false;    // its mesh changed: a ghost of it would trace the new mesh, so it leaves the top
  bool placeDirty = true;      // bounds or level may have changed since the last commit
  bool viewDirty = false;      // listed in Pending::instances

  InstanceRecord() = default;
  InstanceRecord(const InstanceRecord&) = delete;
  InstanceRecord& operator=(const InstanceRecord&) = delete;
  ~InstanceRecord() {
    if (geometry) rtcReleaseGeometry(geometry);
    if (movingGeometry) rtcReleaseGeometry(movingGeometry);
    if (flatGeometry) rtcReleaseGeometry(flatGeometry);
  }
};

// Ids in the top-level scene: the merged static scene is instanced at 0,
// instance i at i + 1 (hits in the moving level are reported so too). In the merged scene, instance i's triangles have
// geometry id i.
inline constexpr std::uint32_t kMergedTopId = 0;
inline std::uint32_t topId(std::uint32_t instance) { return instance + 1; }

struct ResolvedMaterial {
  Material material;
  const Texture* baseColorTexture = nullptr;
  const Texture* emissionTexture = nullptr;
  bool alphaTested = false;  // some hit on it may be cut away or passed (AlphaMode)
  const Texture* metallicRoughnessTexture = nullptr;
  const Texture* transmissionTexture = nullptr;
  const Texture* normalTexture = nullptr;
  VolumeField interior;  // active when the interior medium is textured
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
  // World space to the unit cube over the mesh's object-space bounds, where
  // a textured interior's textures lie (identity otherwise).
  glm::mat4 worldToVolume{1.0f};
  std::uint32_t emissiveOffset = kNotEmissive;  // first triangle in the emitter distribution
  // Moving over the frame interval (null: still): at ray time t the
  // transform is motion->at(t), and the normal transforms follow it.
  const InstanceMotion* motion = nullptr;
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

inline constexpr std::uint32_t kNoId = std::numeric_limits<std::uint32_t>::max();

// What one edit invalidates, for SceneState::edit().
struct Edit {
  std::uint32_t instance = kNoId;  // whose view to refresh
  bool placed = false;             // ... and whose bounds or level may change
  std::uint32_t mesh = kNoId;      // whose data changed: its BVH and its instances' bounds
  bool materials = false;          // resolved materials
  bool lights = false;
  bool emitters = false;       // emission changed: the emitter distribution
  bool placementOnly = false;  // an instance moved and nothing else: appearance stays
};

// Edits since the last commit, which refreshes exactly these.
struct Pending {
  std::vector<std::uint32_t> instances;
  std::vector<std::uint32_t> meshes;
  bool materials = false;
  bool lights = false;
  bool emitters = false;
};

struct SceneState {
  std::shared_ptr<Device> device;
  // Instances that did not move since it was built: rebuilt when instances
  // come or go, or when the ghosts grow too many. Ids as topId().
  RTCScene top = nullptr;
  // Instances whose transform or mesh was edited: few, so such an edit
  // rebuilds a small level instead of the top over every instance (Embree 3
  // has one instancing level, so the two are traced one after the other).
  RTCScene moving = nullptr;
  // Top-level ids (topId()) of the ghosts: instances moved to the moving
  // level whose old copy is still in the top level. The tracer rejects hits
  // on them with a context filter, set only while there are any.
  std::vector<std::uint8_t> ghosts;
  std::uint32_t ghostCount = 0;
  // Static meshes used by exactly one instance are merged, in world space,
  // into one high-quality acceleration structure: no instance traversal and
  // one BVH over interleaved objects. Shared or animated meshes stay instanced.
  RTCScene merged = nullptr;
  RTCGeometry mergedInstance = nullptr;
  bool mergedDirty = true;
  // Over this budget the merged scene holds clusters built as rays reach
  // them (streamed, non-null) instead of every copy.
  TraceMemory traceMemory;
  bool traceMemoryChanged = true;    // the merged level's form is chosen again at commit
  std::uint64_t mergedEstimate = 0;  // its estimated size built whole, as of the last choice
  std::unique_ptr<StreamedGeometry> streamed;
  // What rays traverse, set at commit: the merged scene itself when nothing
  // is instanced (no top level to cross), else the top level.
  RTCScene traversable = nullptr;
  RTCScene movingTraversable = nullptr;  // the moving level if it holds any instance
  std::uint32_t topInstances = 0;
  // Moving-level geometry id -> instance id. Embree's commit walks every id
  // below the highest, so the moving level's ids are dense, not topId().
  std::vector<std::uint32_t> movingIds;
  bool topDirty = true, movingDirty = false;
  // Meshes edited to less than their levelBounds: a level that rebuilds
  // takes their current bounds, so levelBounds shrinks to them then.
  std::vector<std::uint32_t> shrunkMeshes;
  std::uint64_t uid = 0;
  std::uint64_t version = 1;
  std::uint64_t appearance = 1;  // all edits but moves (Scene::appearanceVersion)

  // The one way to edit: restarts accumulation (bumps the version) and
  // records what commit() must refresh.
  void edit(const Edit& e);
  // Lists an instance for commit() to refresh, without an edit of its own.
  void mark(std::uint32_t instance, bool placed);
  Pending pending;

  std::vector<std::unique_ptr<MeshRecord>> meshes;
  std::vector<std::unique_ptr<InstanceRecord>> instances;
  std::vector<std::optional<Material>> materials;
  std::vector<std::shared_ptr<const Texture>> textures;
  std::vector<std::optional<Light>> lights;
  Environment environment;

  // Derived at commit().
  std::vector<ResolvedMaterial> resolved;
  bool materialMedia = false;  // some material has an interior medium
  bool texturedMedia = false;
  bool alphaTested = false;  // some material is: the tracer's context filter tests hits  // ... and some interior is
                             // textured: views hold worldToVolume
  std::vector<InstanceView> views;
  std::vector<Light> activeLights;
  Distribution1D emitters;                        // by power alone (Whitted's light points, lightChoice=power)
  LightTree emitterTree;                          // by what each gives at a point (light_tree.hpp)
  std::vector<EmitterTriangle> emitterTriangles;  // indexed like emitters
  std::vector<EmissiveRange> emissiveRanges;
};

}  // namespace tsr::embree
