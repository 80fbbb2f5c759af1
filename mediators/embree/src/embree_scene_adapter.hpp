#pragma once
// The Embree path tracer's scene adapter: the shared instancing adapter with
// the path tracer's types and translations. Meshes change in place
// (setMeshData), so instance ids and with them the emitter order survive a
// topology edit.
#include "translation.hpp"
#include "tsr/embree/device.hpp"
#include "tsr/embree/error.hpp"
#include "tsr/embree/scene.hpp"
#include "tsr/med/instancing_scene_adapter.hpp"

namespace tsr::med::embree_mediator {

struct EmbreeTypes {
  using Device = embree::Device;
  using Scene = embree::Scene;
  using Environment = embree::Environment;
  using Error = embree::Error;
  static constexpr const char* kName = "embree";
  static constexpr sg::FieldMask kMeshFields = kAllMeshFields;
  static constexpr bool kResizableMeshes = true;
  static constexpr bool kLinesAndPoints = false;  // left out, said at the default log level
  static embree::MeshData mesh(const sg::Geometry& g) { return translateMesh(g); }
  static embree::Material material(const sg::Container* m, const sg::VolumeMaterial* v, const TextureLookup& t) {
    return translateMaterial(m, v, t);
  }
  static embree::Texture texture(const sg::Image& i) { return translateImage(i); }
  static embree::Environment background(const sg::Scene& s, sg::ContainerId b) { return translateBackground(s, b); }
};

using EmbreeSceneAdapter = InstancingSceneAdapter<EmbreeTypes>;

}  // namespace tsr::med::embree_mediator
