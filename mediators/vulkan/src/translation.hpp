#pragma once
// Scene graph values in the rasterizer's vocabulary: materials, the
// background, textures and meshes (lights are shared by every back-end:
// tsr/med/light_translation.hpp). Pure functions; the adapter decides when
// to call them. Material classes follow the Embree mediator's rules so both
// back-ends light the same scene the same way.
#include <functional>
#include <optional>

#include <glm/vec4.hpp>

#include "tsr/med/primitive_of.hpp"
#include "tsr/sg/scene.hpp"
#include "tsr/vk/environment.hpp"
#include "tsr/vk/material.hpp"
#include "tsr/vk/mesh.hpp"
#include "tsr/vk/texture.hpp"

namespace tsr::med::vulkan_mediator {

using TextureLookup = std::function<std::optional<vk::TextureId>(sg::ContainerId image)>;

// SurfaceMaterial: transmission over 0.5 is glass (smooth below roughness
// 0.05) or rough dielectric; else metallic over 0.5 is a mirror (smooth);
// else rough metals, partly metallic surfaces and metallic-roughness
// textures take glTF's metallic-roughness BRDF; else diffuse. Normal maps
// apply to every class; opacity carries over. SimpleMaterial is
// diffuse with opacity 1 - transparency. Emission carries over.
vk::Material translateMaterial(const sg::Container* material, const TextureLookup& textures);
// The surface with the volume inside it (either may be null). A volume
// without a surface, or behind smooth glass of index 1 (glTF's "no
// surface"), is an index-matched boundary: Glass with ior 1. The volume's
// textures are ignored (its factors are used); behind an opaque surface the
// back-end ignores it.
vk::Material translateMaterial(const sg::Container* material, const sg::VolumeMaterial* volume,
                               const TextureLookup& textures);
vk::Medium translateMedium(const sg::VolumeMaterial& volume);

// RGBA; 8-bit sRGB images stay 8-bit (the sampler decodes), the rest float.
vk::Texture translateImage(const sg::Image& image);

// The rasterizer keeps the environment's average as ambient light, and the
// background's medium as fog (its textures ignored).
vk::Environment translateBackground(const sg::Scene& scene, sg::ContainerId background);
vk::Environment translateSky(const sg::Scene& scene, const sg::Background& background);
// What pixels show where nothing is drawn: the environment's average, alpha 0.
glm::vec4 backgroundColour(const vk::Environment& environment);

vk::MeshData translateMesh(const sg::Geometry& geometry);

}  // namespace tsr::med::vulkan_mediator
