#pragma once

#include "tsr/embree/medium.hpp"
#include "tsr/embree/vocabulary.hpp"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <optional>

namespace tsr::embree {

enum class MaterialType {
  Diffuse,     // Lambert; baseColor is the albedo
  Conductor,   // rough GGX metal; baseColor is the Schlick F0
  Dielectric,  // rough GGX glass; baseColor tints transmission
  Mirror,      // perfect specular reflection; baseColor is the reflectance
  Glass,       // smooth dielectric, Fresnel-weighted reflection/refraction
  Interface,   // no surface: an index-matched medium boundary that rays pass straight through
  // glTF 2.0 metallic-roughness (appendix B) with KHR_materials_specular's
  // weight and KHR_materials_transmission: one BSDF whose lobes follow the
  // continuous parameters below. The classes above stay for direct users of
  // the back-end; each is the exact special case it always was.
  MetallicRoughness,
};

// How a surface's alpha (opacity x the base colour texture's alpha)
// covers it: Opaque ignores it; Mask cuts the surface away where alpha is
// below the cut-off; Blend lets a ray pass with probability 1 - alpha
// (stochastic transparency). Cut and passed hits are never seen, by camera
// rays and shadow rays alike.
enum class AlphaMode { Opaque, Mask, Blend };

// An affine map of texture coordinates (KHR_texture_transform), two rows.
struct UvTransform {
  glm::vec3 row0{1.0f, 0.0f, 0.0f};
  glm::vec3 row1{0.0f, 1.0f, 0.0f};
  glm::vec2 operator()(const glm::vec2& uv) const {
    const glm::vec3 h(uv, 1.0f);
    return {glm::dot(row0, h), glm::dot(row1, h)};
  }
  bool identity() const { return row0 == glm::vec3(1, 0, 0) && row1 == glm::vec3(0, 1, 0); }
};
// Below this roughness the specular lobes of MetallicRoughness are perfect
// (delta) reflection and refraction, so smooth mirrors and glass stay sharp.
inline constexpr float kSmoothRoughness = 0.03f;

// Materials are assigned per instance, so one mesh can be shown with several
// materials. Any material can emit: emissive instances become area lights.
struct Material {
  MaterialType type = MaterialType::Diffuse;
  glm::vec3 baseColor{0.8f};
  std::optional<TextureId> baseColorTexture;  // multiplies baseColor (rgb); its alpha multiplies opacity
  UvTransform baseColorUv;
  float opacity = 1.0f;  // in [0, 1]
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  float roughness = 0.5f;  // GGX alpha = roughness^2
  float ior = 1.5f;        // Dielectric and Glass: inside / outside
  // MetallicRoughness only. Textures are linear and multiply the factors.
  float metallic = 0.0f;
  float specular = 1.0f;                              // weight of the dielectric's Fresnel reflection
  float transmission = 0.0f;                          // share of the dielectric that refracts instead of diffusing
  std::optional<TextureId> metallicRoughnessTexture;  // green scales roughness, blue metallic
  std::optional<TextureId> transmissionTexture;       // red scales transmission
  std::optional<TextureId> normalTexture;             // tangent space, (2 * rgb - 1)
  float normalScale = 1.0f;                           // scales the normal's tangent components
  UvTransform metallicRoughnessUv, transmissionUv, normalUv;
  // Radiance leaving the front face (counter-clockwise winding). The light
  // distribution uses luminance(emission) * area; the texture only modulates.
  glm::vec3 emission{0.0f};
  std::optional<TextureId> emissionTexture;
  UvTransform emissionUv;
  // What fills the closed mesh behind the front faces, if anything.
  std::optional<Medium> interior;

  bool isEmissive() const { return emission.x > 0.0f || emission.y > 0.0f || emission.z > 0.0f; }
};

// The fixed class a material is closest to, for the heuristics that think in
// classes (the virtual flash, photon storage, the filters' lobe widths):
// MetallicRoughness by its dominant lobe, every other type as it is.
inline MaterialType closestClass(MaterialType type, float roughness, float metallic, float transmission) {
  if (type != MaterialType::MetallicRoughness) return type;
  const bool smooth = roughness < kSmoothRoughness;
  if (transmission * (1.0f - metallic) > 0.5f) return smooth ? MaterialType::Glass : MaterialType::Dielectric;
  if (metallic > 0.5f) return smooth ? MaterialType::Mirror : MaterialType::Conductor;
  return MaterialType::Diffuse;
}
inline MaterialType closestClass(const Material& m) {
  return closestClass(m.type, m.roughness, m.metallic, m.transmission);
}

}  // namespace tsr::embree
