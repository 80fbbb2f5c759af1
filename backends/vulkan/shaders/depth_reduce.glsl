// Level 0 of the depth pyramid (src/culling/depth_pyramid.hpp): each pixel's farthest
// depth over its samples. Depth is reversed (near = 1), so farthest is the
// minimum; an object nearer than nothing here is behind every sample.
layout(local_size_x = 8, local_size_y = 8) in;

#ifdef MULTISAMPLED
layout(set = 0, binding = 0) uniform sampler2DMS depth;
#else
layout(set = 0, binding = 0) uniform sampler2D depth;
#endif
layout(set = 0, binding = 1, r32f) uniform writeonly image2D level0;

layout(push_constant) uniform Push {
  uvec4 size;    // level 0 (padded to powers of two), the depth attachment
  uint samples;
} pc;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= int(pc.size.x) || p.y >= int(pc.size.y)) return;
  // Padding holds the near plane, so it never makes a texel farther.
  float d = 1.0;
  if (p.x < int(pc.size.z) && p.y < int(pc.size.w)) {
    d = texelFetch(depth, p, 0).r;
#ifdef MULTISAMPLED
    for (int s = 1; s < int(pc.samples); ++s) d = min(d, texelFetch(depth, p, s).r);
#endif
  }
  imageStore(level0, p, vec4(d));
}
