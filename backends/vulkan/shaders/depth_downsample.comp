#version 450
// One level of the depth pyramid from the level below. The sampler reduces
// by minimum (VK_SAMPLER_REDUCTION_MODE_MIN): one bilinear lookup at the
// corner shared by texels 2p..2p+1 returns the farthest of the four. Level 0
// is padded to powers of two, so every texel of the level below is covered
// by exactly one texel here (clamp-to-edge once a side is down to 1).
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D pyramid;  // all levels, min-reducing sampler
layout(set = 0, binding = 1, r32f) uniform writeonly image2D level;

layout(push_constant) uniform Push {
  uvec4 size;  // this level's width, height; the level below's width, height
  uint below;  // the level below's index
} pc;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= int(pc.size.x) || p.y >= int(pc.size.y)) return;
  vec2 uv = vec2(2 * p + 1) / vec2(pc.size.zw);
  imageStore(level, p, vec4(textureLod(pyramid, uv, float(pc.below)).r));
}
