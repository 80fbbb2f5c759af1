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
