// Shared by the mesh and shadow shaders; layouts match src/gpu_types.hpp.

struct Instance {
  mat4 model;
  mat4 normal;
  vec4 positionOffset;  // the mesh's box: positions are 16-bit fractions of it
  vec4 positionScale;
  vec4 uvBox;  // the mesh's uv box (lo, hi - lo), as positionOffset and positionScale
};

// Compact vertex streams (src/scene/vertex_encoding.hpp).
vec4 modelPosition(Instance inst, vec3 fraction) {
  return inst.model * vec4(inst.positionOffset.xyz + fraction * inst.positionScale.xyz, 1.0);
}

vec2 meshUv(Instance inst, vec2 fraction) { return inst.uvBox.xy + fraction * inst.uvBox.zw; }

// Octahedral coordinates to a unit normal; the corner (-1, -1) is no normal (zero).
vec3 octNormal(vec2 e) {
  // Below the nearest real code (-32766: -0.99997), whatever the driver's SNORM rounding.
  if (all(lessThan(e, vec2(-0.99998)))) return vec3(0.0);
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(e.yx)) * vec2(e.x >= 0.0 ? 1.0 : -1.0, e.y >= 0.0 ? 1.0 : -1.0);
  return normalize(n);
}

struct Material {
  vec4 baseColor;
  vec4 emission;
  vec4 params;
  vec4 mediumAbsorption;
  vec4 mediumScattering;
  vec4 mediumEmission;
  vec4 pbr;
  vec4 uv[10];  // two rows per texture slot: base colour, emission, metallic-roughness, normal, occlusion
};


struct Light {
  vec4 position;
  vec4 direction;
  vec4 intensity;
  vec4 cone;
  mat4 shadowMatrix;
};

layout(set = 0, binding = 0) uniform Frame {
  mat4 viewProj;
  vec4 cameraPos;
  vec4 ambient;
  uvec4 counts;
  mat4 invViewProj;
  vec4 viewport;  // pixels across and down, a pixel's camera-space size at unit depth across and down
  vec4 fogAbsorption;
  vec4 fogScattering;
  vec4 fogEmission;
  vec4 emitterAmbient;
  vec4 probeCentre;
  vec4 sceneMin;
  vec4 sceneMax;
  vec4 volumeMin;
  vec4 volumeMax;
  uvec4 volumeCounts;
  vec4 objectProbes[4];
  uvec4 objectProbeSlots;
} frame;

layout(std430, set = 0, binding = 1) readonly buffer Instances { Instance instances[]; };
// Instance slots in draw order: a draw's gl_InstanceIndex indexes this.
layout(std430, set = 0, binding = 2) readonly buffer DrawOrder { uint drawOrder[]; };
layout(std430, set = 0, binding = 3) readonly buffer Materials { Material materials[]; };
const int BASE_COLOR_SLOT = 0, EMISSION_SLOT = 1, METALLIC_ROUGHNESS_SLOT = 2, NORMAL_SLOT = 3, OCCLUSION_SLOT = 4;

// The uv a slot's texture is read at (KHR_texture_transform).
vec2 slotUv(uint material, int slot, vec2 uv) {
  vec3 h = vec3(uv, 1.0);
  return vec2(dot(materials[material].uv[2 * slot].xyz, h), dot(materials[material].uv[2 * slot + 1].xyz, h));
}
layout(std430, set = 0, binding = 4) readonly buffer Lights { Light lights[]; };
layout(set = 0, binding = 5) uniform sampler2DArrayShadow shadowMaps;
// Reversed depth of the nearer of opaque geometry and see-through volumes'
// back faces, for the volumes' thickness (volume.frag).
layout(set = 0, binding = 6) uniform sampler2D volumeBackDepth;
// The split-sum table (src/reflections/brdf_table.hpp): x = n.v, y = roughness.
layout(set = 0, binding = 7) uniform sampler2D brdfTable;
// The environment prefiltered by roughness (Environment::prefiltered()).
layout(set = 0, binding = 8) uniform sampler2D environmentMap;
// The reflection probe's six faces (src/reflections/reflection_probe.cpp).
layout(set = 0, binding = 9) uniform sampler2DArray reflectionProbe;
// The probe prefiltered by roughness (src/reflections/probe_prefilter.hpp).
layout(set = 0, binding = 10) uniform sampler2D probeLevels;
// The irradiance volume (tsr/backend/irradiance_volume.hpp, probe_volume.glsl).
layout(std430, set = 0, binding = 11) readonly buffer IrradianceVolume { vec4 volumeData[]; };

layout(push_constant) uniform Push {
  mat4 lightViewProj;
  uint material;
} pc;
