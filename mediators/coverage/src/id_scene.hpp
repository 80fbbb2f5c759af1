#pragma once
// An id renderer seen through the scene API the shared instancing adapter
// drives (meshes, materials, instances, textures, lights, an environment),
// so the coverage pass syncs through the same path as the path tracer and
// the rasterizer. A material here is only "transparent or not"; changing it
// flips the instances that use it. The id pass has no textures, lights or
// environment: those calls hold nothing. Handles are the back-ends' shared
// ones (backends/common).
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "tsr/backend/light.hpp"
#include "tsr/cov/id_renderer.hpp"

namespace tsr::med::coverage_mediator {

// The adapter's "device": makes an empty id renderer for every conversion.
struct IdRendererSource {
  std::function<std::unique_ptr<cov::IdRenderer>()> make;
};

struct Transparency {
  bool transparent = false;
};
struct NoTexture {};
struct NoEnvironment {};
using backend::MaterialId, backend::TextureId, backend::LightId;

class IdScene {
 public:
  explicit IdScene(const std::shared_ptr<IdRendererSource>& source);

  cov::IdRenderer& renderer() { return *renderer_; }
  // Instances whose transparency flag changed after they were added.
  std::uint64_t transparencyUpdates() const { return transparencyUpdates_; }

  cov::MeshId addMesh(cov::MeshData data) { return renderer_->addMesh(std::move(data)); }
  void setMeshData(cov::MeshId mesh, cov::MeshData data) { renderer_->setMeshData(mesh, std::move(data)); }
  void updateMeshVertices(cov::MeshId mesh, const cov::VertexEdit& edit) { renderer_->updateMeshVertices(mesh, edit); }
  void removeMesh(cov::MeshId mesh) { renderer_->removeMesh(mesh); }

  MaterialId addMaterial(Transparency material);
  void setMaterial(MaterialId id, Transparency material);
  void removeMaterial(MaterialId id);

  cov::InstanceId addInstance(cov::MeshId mesh, MaterialId material, const glm::mat4& world, cov::ObjectId object);
  void setInstanceTransform(cov::InstanceId id, const glm::mat4& world) { renderer_->setInstanceTransform(id, world); }
  void setInstanceMaterial(cov::InstanceId id, MaterialId material);
  void removeInstance(cov::InstanceId id);

  TextureId addTexture(NoTexture) { return TextureId{0}; }
  void removeTexture(TextureId) {}
  LightId addLight(const backend::Light&) { return LightId{0}; }
  void setLight(LightId, const backend::Light&) {}
  void removeLight(LightId) {}
  void setEnvironment(NoEnvironment) {}

 private:
  struct Material {
    bool transparent = false;
    std::unordered_set<cov::InstanceId> users;
  };
  Material& material(MaterialId id);
  void setTransparent(cov::InstanceId id, bool transparent);

  std::unique_ptr<cov::IdRenderer> renderer_;
  std::vector<std::optional<Material>> materials_;  // by MaterialId
  std::unordered_map<cov::InstanceId, MaterialId> instanceMaterials_;
  std::uint64_t transparencyUpdates_ = 0;
};

}  // namespace tsr::med::coverage_mediator
