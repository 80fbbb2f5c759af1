#version 450
#include "common.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec2 inNormal;  // octahedral
layout(location = 2) in vec2 inUv;

layout(location = 0) out vec3 worldPos;
layout(location = 1) out vec3 worldNormal;
layout(location = 2) out vec2 uv;
layout(location = 3) flat out uint instanceSlot;

void main() {
  instanceSlot = drawOrder[gl_InstanceIndex];
  Instance inst = instances[instanceSlot];
  vec4 p = modelPosition(inst, inPosition);
  worldPos = p.xyz;
  // A zero normal (mesh without normals) stays zero: the fragment shader
  // then uses the flat face normal.
  worldNormal = mat3(inst.normal) * octNormal(inNormal);
  uv = meshUv(inst, inUv);
  gl_Position = frame.viewProj * p;
  gl_PointSize = 1.0;  // read only when drawing points: one pixel, as glTF viewers draw them
}
