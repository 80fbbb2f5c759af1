#pragma once

#include "tsr/cov/id_buffer.hpp"
#include "tsr/cov/ids.hpp"
#include "tsr/cov/mesh.hpp"
#include "tsr/cov/vocabulary.hpp"

#include <glm/mat4x4.hpp>

#include <cstddef>
#include <cstdint>
#include <span>

namespace tsr::cov {

// One placement of a mesh. A transparent instance neither occludes nor is
// counted: pixels behind it show whatever opaque object lies further back,
// as a culling service wants (what is seen through glass must be loaded).
struct Instance {
  MeshId mesh{};
  glm::mat4 transform{1.0f};
  ObjectId object = 1;  // must not be kBackground
  bool transparent = false;
};

// The interface every id pass implements (Embree ray tracing here; a
// rasterizer can follow): a small scene of meshes and instances that is
// edited incrementally, and render(), which shoots one sample through the
// centre of every pixel of a region. Edits are cheap and deferred until the
// next render. Not thread-safe: do not edit while a render runs.
class IdRenderer {
 public:
  virtual ~IdRenderer() = default;

  virtual MeshId addMesh(MeshData data) = 0;
  // Replaces everything, topology included.
  virtual void setMeshData(MeshId mesh, MeshData data) = 0;
  // Takes the edit's range of positions (the id pass has no normals);
  // topology unchanged.
  virtual void updateMeshVertices(MeshId mesh, const VertexEdit& edit) = 0;
  // Throws Error while an instance still uses the mesh.
  virtual void removeMesh(MeshId mesh) = 0;

  virtual InstanceId addInstance(const Instance& instance) = 0;
  virtual void setInstanceTransform(InstanceId instance, const glm::mat4& transform) = 0;
  virtual void setInstanceObject(InstanceId instance, ObjectId object) = 0;
  virtual void setInstanceTransparent(InstanceId instance, bool transparent) = 0;
  virtual void removeInstance(InstanceId instance) = 0;

  virtual std::size_t meshCount() const = 0;
  virtual std::size_t instanceCount() const = 0;

  // Throws Error for an invalid camera or region.
  virtual IdBuffer render(const Camera& camera, const Region& region) = 0;
};

}  // namespace tsr::cov
