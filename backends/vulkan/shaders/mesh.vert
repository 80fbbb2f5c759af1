#version 450
#include "common.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;

layout(location = 0) out vec3 worldPos;
layout(location = 1) out vec3 worldNormal;
layout(location = 2) out vec2 uv;

void main() {
  Instance inst = instances[drawOrder[gl_InstanceIndex]];
  vec4 p = inst.model * vec4(inPosition, 1.0);
  worldPos = p.xyz;
  // A zero normal (mesh without normals) stays zero: the fragment shader
  // then uses the flat face normal.
  worldNormal = mat3(inst.normal) * inNormal;
  uv = inUv;
  gl_Position = frame.viewProj * p;
}
