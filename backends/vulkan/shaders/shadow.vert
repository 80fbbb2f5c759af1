#version 450
#include "common.glsl"

layout(location = 0) in vec3 inPosition;

void main() {
  Instance inst = instances[drawOrder[gl_InstanceIndex]];
  gl_Position = pc.lightViewProj * modelPosition(inst, inPosition);
}
