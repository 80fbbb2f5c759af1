#version 450
#define MULTISAMPLED 1
#include "depth_reduce.glsl"
