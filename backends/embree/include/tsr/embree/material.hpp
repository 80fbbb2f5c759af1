#pragma once

#include "tsr/embree/ids.hpp"
#include "tsr/embree/medium.hpp"

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
};

// Materials are assigned per instance, so one mesh can be shown with several
// materials. Any material can emit: emissive instances become area lights.
struct Material {
  MaterialType type = MaterialType::Diffuse;
  glm::vec3 baseColor{0.8f};
  std::optional<TextureId> baseColorTexture;  // multiplies baseColor (rgb)
  float roughness = 0.5f;                     // GGX alpha = roughness^2
  float ior = 1.5f;                           // Dielectric and Glass: inside / outside
  // Radiance leaving the front face (counter-clockwise winding). The light
  // distribution uses luminance(emission) * area; the texture only modulates.
  glm::vec3 emission{0.0f};
  std::optional<TextureId> emissionTexture;
  // What fills the closed mesh behind the front faces, if anything.
  std::optional<Medium> interior;

  bool isEmissive() const { return emission.x > 0.0f || emission.y > 0.0f || emission.z > 0.0f; }
};

}  // namespace tsr::embree
