#pragma once

#include "tsr/vk/medium.hpp"
#include "tsr/vk/vocabulary.hpp"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <optional>

namespace tsr::vk {

// The Embree back-end's material types; here evaluated for direct light only.
enum class MaterialType {
  Diffuse,     // Lambert; baseColor is the albedo
  Conductor,   // rough GGX metal; baseColor is the Schlick F0
  Dielectric,  // rough GGX glass: reflection, and transmission of lights behind it
  Mirror,      // perfect specular: no direct light from point-like lights, reflects the ambient term
  Glass,       // smooth dielectric: likewise
  // glTF 2.0's metallic-roughness BRDF (specification, appendix B): Lambert
  // diffuse of baseColor (1 - metallic) under a GGX/Smith specular with
  // Schlick Fresnel, F0 = mix(0.04, baseColor, metallic). The ambient term
  // is the environment's average times the split-sum directional albedo,
  // with multiple-scattering compensation, so white materials reflect all
  // of a uniform environment.
  MetallicRoughness,
};

// An affine map of a texture's coordinates (KHR_texture_transform): two rows.
struct UvTransform {
  glm::vec3 row0{1.0f, 0.0f, 0.0f};
  glm::vec3 row1{0.0f, 1.0f, 0.0f};
  glm::vec2 operator()(const glm::vec2& uv) const {
    const glm::vec3 h(uv, 1.0f);
    return {glm::dot(row0, h), glm::dot(row1, h)};
  }
};

// A material's textures, in the order of their descriptor bindings and uv transforms.
enum class TextureSlot { BaseColor, Emission, MetallicRoughness, Normal, Occlusion, Count };
inline constexpr std::size_t kTextureSlots = static_cast<std::size_t>(TextureSlot::Count);

struct Material {
  MaterialType type = MaterialType::Diffuse;
  glm::vec3 baseColor{0.8f};
  std::optional<TextureId> baseColorTexture;  // multiplies baseColor (rgb); its alpha multiplies opacity
  float roughness = 0.5f;                     // GGX alpha = roughness^2
  float ior = 1.5f;                           // Dielectric and Glass: inside / outside
  glm::vec3 emission{0.0f};                   // radiance leaving the front (counter-clockwise) face
  std::optional<TextureId> emissionTexture;   // multiplies emission (rgb)
  float metallic = 0.0f;                      // MetallicRoughness only
  // MetallicRoughness only, linear: green multiplies roughness, blue metallic.
  std::optional<TextureId> metallicRoughnessTexture;
  // Tangent-space normals (linear, +x along u, +y up the image, i.e. along
  // -v), any material type; the tangent frame comes from screen-space
  // derivatives of position and uv, so meshes need no tangents.
  std::optional<TextureId> normalTexture;
  float normalScale = 1.0f;  // scales the map's x and y
  // Ambient occlusion (linear, red channel) darkens the ambient and the
  // image-based light, not the lights: 1 + strength * (occlusion - 1).
  std::optional<TextureId> occlusionTexture;
  float occlusionStrength = 1.0f;
  std::array<UvTransform, kTextureSlots> uv{};  // by TextureSlot
  // Below 1 the instance is alpha blended: drawn after opaque geometry,
  // sorted back to front, without depth writes, and casts no shadow.
  float opacity = 1.0f;
  // Above 0, alpha (opacity x the base colour texture's alpha) below it
  // cuts the surface away (glTF's MASK) and the rest is opaque: drawn with
  // the opaque geometry; its shadow is cut alike.
  float alphaCutoff = 0.0f;
  // What fills the (closed) mesh. Shown only behind a surface light passes
  // through (Glass or Dielectric; an index-matched boundary is Glass with
  // ior 1): the instance is then drawn see-through, after opaque geometry,
  // attenuating what lies behind it by the thickness its back faces give.
  // Behind an opaque surface nothing shows it, so it is ignored.
  std::optional<Medium> interior;

  std::array<std::optional<TextureId>, kTextureSlots> textures() const {
    return {baseColorTexture, emissionTexture, metallicRoughnessTexture, normalTexture, occlusionTexture};
  }
  bool isEmissive() const { return emission.x > 0.0f || emission.y > 0.0f || emission.z > 0.0f; }
  bool isVolume() const {
    return interior && !interior->empty() && (type == MaterialType::Glass || type == MaterialType::Dielectric);
  }
  // Drawn after opaque geometry, sorted back to front, without depth writes,
  // casting no shadow: blended surfaces and see-through volumes.
  bool isTransparent() const { return (alphaCutoff <= 0.0f && opacity < 1.0f) || isVolume(); }
};

}  // namespace tsr::vk
