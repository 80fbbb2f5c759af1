#version 450
// Id pass: positions only; each instance's object id goes flat to the fragment.
// Its own descriptor layout (src/passes/id_pass.cpp), not common.glsl's.

struct Instance {
  mat4 model;
  mat4 normal;
  vec4 positionOffset;  // the mesh's box: positions are 16-bit fractions of it
  vec4 positionScale;
  vec4 uvBox;  // the mesh's uv box (lo, hi - lo), as positionOffset and positionScale
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
  Instance inst = instances[slot];
  // As common.glsl's modelPosition: positions are 16-bit fractions of the mesh's box.
  gl_Position = frame.viewProj * (inst.model * vec4(inst.positionOffset.xyz + inPosition * inst.positionScale.xyz, 1.0));
  gl_PointSize = 1.0;  // points cover one pixel, as the colour pass draws them
}
