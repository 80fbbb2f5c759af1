#pragma once

#include "tsr/embree/device.hpp"
#include "tsr/embree/environment.hpp"
#include "tsr/embree/material.hpp"
#include "tsr/embree/mesh.hpp"
#include "tsr/embree/texture.hpp"
#include "tsr/embree/vocabulary.hpp"

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <memory>
#include <span>

namespace tsr::embree {

struct SceneState;

// How much memory the path tracer's copy of the scene's single-use static
// meshes (their world-space positions and BVH, the merged level) may take.
// Within it they are built whole at commit; over it they are grouped in
// clusters of about `clusterTriangles`, each built when a ray first reaches
// it and dropped, least recently used first, once the built ones pass
// `bytes` (src/scene/streamed_geometry.hpp). The default is a sixth of the
// machine's memory (of a container's cgroup limit when lower): the 50 M-triangle plant (about 2.6 GB) is built whole
// on a 24 GB machine, the 300 M one streamed.
struct TraceMemory {
  std::uint64_t bytes = defaultBytes();
  std::uint32_t clusterTriangles = 1u << 19;
  static std::uint64_t defaultBytes();
  bool operator==(const TraceMemory&) const = default;
};

// What the merged level holds, as of now.
struct TraceMemoryUse {
  std::uint64_t wholeBytes = 0;  // estimated size of the merged level built whole
  bool streamed = false;         // built by clusters as rays reach them
  std::uint32_t clusters = 0;    // in the current partition
  std::uint32_t built = 0;       // clusters built and not dropped
  std::uint64_t heldBytes = 0;
  std::uint64_t builds = 0;     // since the scene was made
  std::uint64_t evictions = 0;  // built clusters dropped for the budget
};

// The back-end's own scene: meshes (one Embree scene each) instanced into a
// top-level Embree scene. Every edit bumps version(), which is what the
// renderer compares to decide whether accumulation must restart. Edits are
// cheap and deferred: commit() (called by the renderer) rebuilds only what
// changed. Not thread-safe: do not edit while a pass renders this scene.
class Scene {
 public:
  explicit Scene(std::shared_ptr<Device> device);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  MeshId addMesh(MeshData data);
  // Takes the edit's range of positions (and normals, when it carries them).
  // Topology is unchanged, so animated meshes refit.
  void updateMeshVertices(MeshId mesh, const VertexEdit& edit);
  // Replaces everything, topology included (rebuilds that mesh's BVH).
  void setMeshData(MeshId mesh, MeshData data);
  // Throws if an instance still uses the mesh.
  void removeMesh(MeshId mesh);

  InstanceId addInstance(MeshId mesh, MaterialId material, const glm::mat4& transform);
  void setInstanceTransform(InstanceId instance, const glm::mat4& transform);
  // Motion over the frame interval: the transform at its start (ray time 0)
  // and at its end (ray time 1), interpolated linearly between, as Embree
  // interpolates the instance. Equal matrices keep the instance still. A
  // moving emitter lights the scene only where paths hit it (no light
  // sampling: its triangles are not at one place).
  void setInstanceTransform(InstanceId instance, const glm::mat4& transform, const glm::mat4& atEnd);
  void setInstanceMaterial(InstanceId instance, MaterialId material);
  void removeInstance(InstanceId instance);

  MaterialId addMaterial(const Material& material);
  void setMaterial(MaterialId id, const Material& material);
  void removeMaterial(MaterialId id);  // throws if an instance uses it

  TextureId addTexture(Texture texture);
  void removeTexture(TextureId id);  // throws if a material uses it

  LightId addLight(const Light& light);
  void setLight(LightId id, const Light& light);
  void removeLight(LightId id);

  void setEnvironment(Environment environment);

  // Commits pending edits to Embree and refreshes the derived data of what
  // they touched (views, emitters only if an emitter changed); idempotent.
  void commit();

  // Takes effect at the next commit (the merged level is placed again if
  // it changes form); the budget is not an edit: images stay the same but
  // for rays through shared edges, and accumulation goes on.
  void setTraceMemory(const TraceMemory& budget);
  TraceMemoryUse traceMemoryUse() const;

  std::uint64_t version() const;
  // Bumped by every edit but setInstanceTransform: equal, the scene differs
  // at most by where instances stand (what a reprojected history survives).
  std::uint64_t appearanceVersion() const;
  std::uint64_t uid() const;  // distinguishes scenes for the accumulation key
  std::size_t instanceCount() const;
  std::size_t meshCount() const;
  // The box around every instance as last committed; false when the scene
  // is empty.
  bool bounds(glm::vec3& lo, glm::vec3& hi) const;

  // For benchmarks that trace raw rays; valid after commit(). Instances whose
  // transform or mesh was edited are in a second level the renderer traces
  // after this one (leaving ghosts here that the renderer skips), so raw
  // rays see only scenes that were never edited.
  RTCScene embreeScene() const;
  const SceneState& state() const { return *state_; }

 private:
  std::unique_ptr<SceneState> state_;
};

}  // namespace tsr::embree
