#version 450
#include "common.glsl"

// mesh.vert without uvs: volume.frag reads none.

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;

layout(location = 0) out vec3 worldPos;
layout(location = 1) out vec3 worldNormal;

void main() {
  Instance inst = instances[drawOrder[gl_InstanceIndex]];
  vec4 p = inst.model * vec4(inPosition, 1.0);
  worldPos = p.xyz;
  worldNormal = mat3(inst.normal) * inNormal;
  gl_Position = frame.viewProj * p;
}
