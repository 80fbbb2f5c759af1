#version 450
// Id pass: positions only; each instance's object id goes flat to the fragment.
// Its own descriptor layout (src/passes/id_pass.cpp), not common.glsl's.

struct Instance {
  mat4 model;
  mat4 normal;
};

layout(set = 0, binding = 0) uniform Frame { mat4 viewProj; } frame;
layout(std430, set = 0, binding = 1) readonly buffer Instances { Instance instances[]; };
layout(std430, set = 0, binding = 2) readonly buffer DrawOrder { uint drawOrder[]; };
layout(std430, set = 0, binding = 3) readonly buffer Objects { uint objects[]; };

layout(location = 0) in vec3 inPosition;
layout(location = 0) flat out uint objectId;

void main() {
  uint slot = drawOrder[gl_InstanceIndex];
  objectId = objects[slot];
  gl_Position = frame.viewProj * (instances[slot].model * vec4(inPosition, 1.0));
}
