#version 450
#include "depth_reduce.glsl"
