#version 450

layout(location = 0) in vec3 inPosition;
layout(std430, set = 0, binding = 0) readonly buffer Instances { mat4 models[]; };
layout(push_constant) uniform Push { mat4 viewProj; } pc;

void main() { gl_Position = pc.viewProj * (models[gl_InstanceIndex] * vec4(inPosition, 1.0)); }
