// Shared by the mesh and shadow shaders; layouts match src/gpu_types.hpp.

struct Instance {
  mat4 model;
  mat4 normal;
};

struct Material {
  vec4 baseColor;
  vec4 emission;
  vec4 params;
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
} frame;

layout(std430, set = 0, binding = 1) readonly buffer Instances { Instance instances[]; };
// Instance slots in draw order: a draw's gl_InstanceIndex indexes this.
layout(std430, set = 0, binding = 2) readonly buffer DrawOrder { uint drawOrder[]; };
layout(std430, set = 0, binding = 3) readonly buffer Materials { Material materials[]; };
layout(std430, set = 0, binding = 4) readonly buffer Lights { Light lights[]; };
layout(set = 0, binding = 5) uniform sampler2DArrayShadow shadowMaps;

layout(push_constant) uniform Push {
  mat4 lightViewProj;
  uint material;
} pc;
