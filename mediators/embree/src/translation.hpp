#pragma once
// Scene graph values in the path tracer's vocabulary: materials, the
// background, textures and meshes (lights are shared by every back-end:
// tsr/med/light_translation.hpp). Pure functions; the adapter decides
// when to call them.
#include <functional>
#include <optional>

#include "tsr/embree/environment.hpp"
#include "tsr/embree/material.hpp"
#include "tsr/embree/mesh.hpp"
#include "tsr/embree/texture.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::med::embree_mediator {

using TextureLookup = std::function<std::optional<embree::TextureId>(sg::ContainerId image)>;

// SurfaceMaterial: transmission over 0.5 is glass (smooth below roughness
// 0.05) or rough dielectric; else metallic over 0.5 is a mirror (smooth) or
// rough conductor; else diffuse. SimpleMaterial is diffuse; its
// transparency is not modelled by the path tracer. Emission carries over.
embree::Material translateSurface(const sg::Container* material, const TextureLookup& textures);
// The surface with the volume inside it: a volume without a surface
// material has an index-matched boundary (MaterialType::Interface).
embree::Material translateMaterial(const sg::Container* material, const sg::VolumeMaterial* volume,
                                   const TextureLookup& textures);
// A volume's coefficients, sanitised (the scene's fog: no textures) ...
embree::Medium translateMedium(const sg::VolumeMaterial& volume);
// ... and with its textures, for a closed mesh's interior.
embree::Medium translateMedium(const sg::VolumeMaterial& volume, const TextureLookup& textures);

// RGBA, linear; sRGB 8-bit images are decoded.
embree::Texture translateImage(const sg::Image& image);

// Colour, gradient (baked into a small lat-long map) or environment image.
// With the background's medium (fog), if it names one.
embree::Environment translateBackground(const sg::Scene& scene, sg::ContainerId background);
embree::Environment translateSky(const sg::Scene& scene, const sg::Background& background);

embree::MeshData translateMesh(const sg::Geometry& geometry);

}  // namespace tsr::med::embree_mediator
