#pragma once
// Scene graph values in the form every back-end's translation starts from:
// linear RGBA texels, a baked gradient sky and the class of surface a
// material describes (lights: light_translation.hpp). One place, so that the
// back-ends agree (the cross-back-end tests compare their images).
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "tsr/sg/scene.hpp"

namespace tsr::med {

// RGBA in linear units, one per pixel, row 0 at the top; sRGB 8-bit decoded,
// grey and grey+alpha expanded.
std::vector<glm::vec4> linearTexels(const sg::Image& image);

// A background gradient as a lat-long map (rows follow elevation, the top
// row at the zenith).
struct BakedSky {
  std::uint32_t width = 8, height = 64;
  std::vector<glm::vec4> texels;
};
BakedSky bakeGradient(const sg::Background& background);

// How a SurfaceMaterial maps onto the surface models back-ends share:
// transmission over 0.5 is glass (smooth below roughness 0.05) or a rough
// dielectric; else metallic over 0.5 is a mirror (smooth below 0.02) or a
// rough conductor; else diffuse.
enum class SurfaceClass { Diffuse, Conductor, Dielectric, Mirror, Glass };
SurfaceClass classify(const sg::SurfaceMaterial& material);

// A texture slot's transform (KHR_texture_transform) as two rows; a
// malformed one (NaN, infinity) is the identity.
std::pair<glm::vec3, glm::vec3> usableUvTransform(const sg::SurfaceMaterial& material, sg::TextureSlot slot);

}  // namespace tsr::med
