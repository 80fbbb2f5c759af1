#version 450
#include "common.glsl"

// mesh.vert without uvs: volume.frag reads none.

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec2 inNormal;  // octahedral

layout(location = 0) out vec3 worldPos;
layout(location = 1) out vec3 worldNormal;

void main() {
  Instance inst = instances[drawOrder[gl_InstanceIndex]];
  vec4 p = modelPosition(inst, inPosition);
  worldPos = p.xyz;
  worldNormal = mat3(inst.normal) * octNormal(inNormal);
  gl_Position = frame.viewProj * p;
}
