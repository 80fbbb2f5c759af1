#pragma once

#include "tsr/vk/ids.hpp"
#include "tsr/vk/medium.hpp"

#include <glm/vec3.hpp>

#include <optional>

namespace tsr::vk {

// The Embree back-end's material types; here evaluated for direct light only.
enum class MaterialType {
  Diffuse,     // Lambert; baseColor is the albedo
  Conductor,   // rough GGX metal; baseColor is the Schlick F0
  Dielectric,  // rough GGX glass: reflection, and transmission of lights behind it
  Mirror,      // perfect specular: no direct light from point-like lights, reflects the ambient term
  Glass,       // smooth dielectric: likewise
};

struct Material {
  MaterialType type = MaterialType::Diffuse;
  glm::vec3 baseColor{0.8f};
  std::optional<TextureId> baseColorTexture;  // multiplies baseColor (rgb); its alpha multiplies opacity
  float roughness = 0.5f;                     // GGX alpha = roughness^2
  float ior = 1.5f;                           // Dielectric and Glass: inside / outside
  glm::vec3 emission{0.0f};                   // radiance leaving the front (counter-clockwise) face
  std::optional<TextureId> emissionTexture;   // multiplies emission (rgb)
  // Below 1 the instance is alpha blended: drawn after opaque geometry,
  // sorted back to front, without depth writes, and casts no shadow.
  float opacity = 1.0f;
  // What fills the (closed) mesh. Shown only behind a surface light passes
  // through (Glass or Dielectric; an index-matched boundary is Glass with
  // ior 1): the instance is then drawn see-through, after opaque geometry,
  // attenuating what lies behind it by the thickness its back faces give.
  // Behind an opaque surface nothing shows it, so it is ignored.
  std::optional<Medium> interior;

  bool isEmissive() const { return emission.x > 0.0f || emission.y > 0.0f || emission.z > 0.0f; }
  bool isVolume() const {
    return interior && !interior->empty() && (type == MaterialType::Glass || type == MaterialType::Dielectric);
  }
  // Drawn after opaque geometry, sorted back to front, without depth writes,
  // casting no shadow: blended surfaces and see-through volumes.
  bool isTransparent() const { return opacity < 1.0f || isVolume(); }
};

}  // namespace tsr::vk
