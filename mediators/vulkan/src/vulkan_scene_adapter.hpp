#pragma once
// The Vulkan rasterizer's scene adapter: the shared instancing adapter with
// the rasterizer's types and translations. Vulkan meshes are fixed in size,
// so a topology edit builds the mesh again and places its instances again.
#include "translation.hpp"
#include "tsr/med/instancing_scene_adapter.hpp"
#include "tsr/vk/device.hpp"
#include "tsr/vk/error.hpp"
#include "tsr/vk/scene.hpp"

namespace tsr::med::vulkan_mediator {

struct VulkanTypes {
  using Device = vk::Device;
  using Scene = vk::Scene;
  using Environment = vk::Environment;
  using Error = vk::Error;
  static constexpr const char* kName = "vulkan";
  static constexpr sg::FieldMask kMeshFields = kAllMeshFields;
  static constexpr bool kResizableMeshes = false;
  static constexpr bool kLinesAndPoints = true;
  static vk::MeshData mesh(const sg::Geometry& g) { return translateMesh(g); }
  static vk::Material material(const sg::Container* m, const sg::VolumeMaterial* v, const TextureLookup& t) {
    return translateMaterial(m, v, t);
  }
  static vk::Texture texture(const sg::Image& i) { return translateImage(i); }
  static vk::Environment background(const sg::Scene& s, sg::ContainerId b) { return translateBackground(s, b); }
};

using VulkanSceneAdapter = InstancingSceneAdapter<VulkanTypes>;

}  // namespace tsr::med::vulkan_mediator
