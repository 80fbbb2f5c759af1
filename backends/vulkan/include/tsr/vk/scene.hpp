#pragma once

#include "tsr/vk/device.hpp"
#include "tsr/vk/environment.hpp"
#include "tsr/vk/material.hpp"
#include "tsr/vk/mesh.hpp"
#include "tsr/vk/texture.hpp"
#include "tsr/vk/vocabulary.hpp"

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <memory>
#include <span>

namespace tsr::vk {

struct SceneState;

// The back-end's own scene. Each mesh lives once in device memory (positions,
// normals, uvs, indices) and is shared by all instances that use it. Instance
// transforms live in a host-visible storage buffer, so moving an instance
// writes 128 bytes and never touches geometry. Uploads happen inside the edit
// call. Not thread-safe; do not edit while a render of this scene runs.
class Scene {
 public:
  explicit Scene(std::shared_ptr<Device> device);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  MeshId addMesh(const MeshData& data);
  // Takes the edit's range of positions (and normals, when it carries them),
  // uploading only that range, unless the bounds of the edit's positions
  // (all of them, exact) differ from the box the mesh is quantized in: then
  // every position is stored again from them, as a new mesh of them would be.
  void updateMeshVertices(MeshId mesh, const VertexEdit& edit);
  void removeMesh(MeshId mesh);  // throws if an instance still uses it

  InstanceId addInstance(MeshId mesh, MaterialId material, const glm::mat4& transform);
  void setInstanceTransform(InstanceId instance, const glm::mat4& transform);
  void setInstanceMaterial(InstanceId instance, MaterialId material);
  // The id the id pass (Renderer::renderIds) writes for this instance;
  // index(instance) + 1 until set. Writes 4 bytes.
  void setInstanceObject(InstanceId instance, std::uint32_t object);
  std::uint32_t instanceObject(InstanceId instance) const;
  void removeInstance(InstanceId instance);

  MaterialId addMaterial(const Material& material);
  void setMaterial(MaterialId id, const Material& material);
  void removeMaterial(MaterialId id);  // throws if an instance uses it

  TextureId addTexture(const Texture& texture);
  void removeTexture(TextureId id);  // throws if a material uses it

  LightId addLight(const Light& light);
  void setLight(LightId id, const Light& light);
  void removeLight(LightId id);

  void setEnvironment(const Environment& environment);

  std::uint64_t version() const;  // bumped by every edit
  std::size_t instanceCount() const;
  std::size_t meshCount() const;

  // Bytes copied into mesh buffers (vertices and indices) since creation.
  std::uint64_t geometryBytesUploaded() const;
  // Device memory the geometry holds now (the arena's blocks, filled or not).
  std::uint64_t geometryBytesHeld() const;
  // Bytes of instance records written since creation.
  std::uint64_t instanceBytesWritten() const;

  const Device& device() const;
  // For the renderer.
  SceneState& state() { return *state_; }

 private:
  std::unique_ptr<SceneState> state_;
};

}  // namespace tsr::vk
