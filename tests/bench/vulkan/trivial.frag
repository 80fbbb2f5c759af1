#version 450

layout(location = 0) out vec4 outColour;

void main() { outColour = vec4(0.8, 0.8, 0.8, 1.0); }
