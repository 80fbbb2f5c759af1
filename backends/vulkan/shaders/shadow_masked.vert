#version 450
#include "common.glsl"

// The shadow pass for glTF MASK materials: as shadow.vert, plus the uv the
// fragment shader cuts the surface by.
layout(location = 0) in vec3 inPosition;
layout(location = 2) in vec2 inUv;

layout(location = 0) out vec2 uv;

void main() {
  Instance inst = instances[drawOrder[gl_InstanceIndex]];
  uv = meshUv(inst, inUv);
  gl_Position = pc.lightViewProj * modelPosition(inst, inPosition);
}
