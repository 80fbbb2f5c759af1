#pragma once

#include "tsr/vk/material.hpp"

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <cstdint>

namespace tsr::vk {

// Layouts shared with shaders/common.glsl (std140/std430 agree here: only
// vec4 and mat4 members). Change both together.

struct GpuInstance {
  glm::mat4 model;
  glm::mat4 normal;          // inverse transpose of model's 3x3, padded
  glm::vec4 positionOffset;  // the mesh's box (vertex_encoding.hpp): xyz lo
  glm::vec4 positionScale;   // xyz hi - lo; w the mesh's uv units a length unit (uv_density.hpp)
  glm::vec4 uvBox;           // the mesh's uv box: lo, hi - lo
};
static_assert(sizeof(GpuInstance) == 176, "shaders/common.glsl, ids.vert and cull.comp read 176-byte records");

// Type and textures select a specialised pipeline instead (see mesh.frag).
struct GpuMaterial {
  glm::vec4 baseColor;  // rgb, opacity
  glm::vec4 emission;   // rgb, unused
  glm::vec4 params;     // GGX alpha, ior, occlusion strength, unused
  // Material::interior (zero without one): see volume.frag.
  glm::vec4 mediumAbsorption;       // rgb, Henyey-Greenstein g
  glm::vec4 mediumScattering;       // rgb, unused
  glm::vec4 mediumEmission;         // rgb, unused
  glm::vec4 pbr;                    // roughness, metallic, normal scale, alpha cut-off (0: none)
  glm::vec4 uv[2 * kTextureSlots];  // Material::uv: two rows (xyz) per TextureSlot
};

enum : std::uint32_t { kGpuPoint = 0, kGpuSpot = 1, kGpuDirectional = 2, kGpuEmitter = 3 };

// Emitter patches (emitter_lights.hpp) use direction = normal, intensity =
// (radiance, area) and cone.x = directional area.
struct GpuLight {
  glm::vec4 position;   // xyz, type
  glm::vec4 direction;  // normalized travel direction, shadow layer (< 0: none)
  glm::vec4 intensity;  // W/sr, or W/m^2 for directional
  glm::vec4
      cone;  // cos inner, cos outer, normal offset (world units, per unit distance for spots/emitters), 1 / map size
  glm::mat4 shadowMatrix;
};

struct GpuFrame {
  glm::mat4 viewProj;
  glm::vec4 cameraPos;
  glm::vec4 ambient;  // average environment radiance
  glm::uvec4 counts;  // light count, unused...
  glm::mat4 invViewProj;
  glm::vec4 viewport;        // width, height of the region in pixels; a pixel's size at unit depth (viewportOf)
  glm::vec4 fogAbsorption;   // the environment's fog (zero without): rgb, g
  glm::vec4 fogScattering;   // rgb, unused
  glm::vec4 fogEmission;     // rgb, unused
  glm::vec4 emitterAmbient;  // the emitters' part of `ambient`, added to the prefiltered environment
  glm::vec4 probeCentre;     // the reflection probe's centre, w: 0 none, 1 for mirrors, 2 also rough reflections
  glm::vec4 sceneMin;        // the scene's bounds, which probe lookups are projected onto
  glm::vec4 sceneMax;
  glm::vec4 volumeMin;  // the irradiance volume's box, w: 1 when there is one
  glm::vec4 volumeMax;
  glm::uvec4 volumeCounts;  // probes per axis, probe count
  // Mirrors' and glass's own reflection probes (Renderer::Impl::objectProbes):
  // centre of the object's box, w 1 (0: none), and the instance slot it
  // belongs to; probe k's faces are layers 6 (k + 1) .. 6 (k + 1) + 5 of the
  // probe image.
  glm::vec4 objectProbes[4];
  glm::uvec4 objectProbeSlots;
};

struct PushConstants {
  glm::mat4 lightViewProj;  // shadow pass only
  std::uint32_t material = 0;
  std::uint32_t pad[3] = {0, 0, 0};
};

}  // namespace tsr::vk
