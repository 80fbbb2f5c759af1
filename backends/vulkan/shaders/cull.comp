#version 450
// Two-phase occlusion culling (src/culling/occlusion_culler.hpp). One invocation per
// opaque draw position. Phase 0 (early): a draw command for each object seen
// last frame and inside the frustum. Phase 1 (late): every object's bounds
// against the depth pyramid of what the early draws left; visible ones not
// drawn early get a command. Phase 2 (after the frame): every object against
// the pyramid of the finished frame, which is what the next early phase
// draws. Commands keep their positions, so the draw order is the full draw's.
layout(local_size_x = 64) in;

struct Instance {
  mat4 model;
  mat4 normal;
  vec4 positionOffset;  // the mesh's box: positions are 16-bit fractions of it
  vec4 positionScale;
  vec4 uvBox;  // the mesh's uv box (lo, hi - lo), as positionOffset and positionScale
};

struct Record {
  uvec4 info;  // instance slot, index count, first index, vertex offset
  vec4 lo;     // mesh bounds, object space
  vec4 hi;
};

struct Command {
  uint indexCount;
  uint instanceCount;
  uint firstIndex;
  int vertexOffset;
  uint firstInstance;
};

layout(std430, set = 0, binding = 0) readonly buffer Records { Record records[]; };
layout(std430, set = 0, binding = 1) readonly buffer Instances { Instance instances[]; };
layout(std430, set = 0, binding = 2) buffer Visibility { uint visible[]; };
layout(std430, set = 0, binding = 3) buffer Early { Command early[]; };
layout(std430, set = 0, binding = 4) writeonly buffer Late { Command late[]; };
layout(set = 0, binding = 5) uniform sampler2D pyramid;  // read with texelFetch only

layout(push_constant) uniform Push {
  mat4 viewProj;
  uvec4 params;  // count, phase, width, height
} pc;

// Clip-space corners of the object's bounds; false when the box lies outside
// one clip plane (then no fragment of it survives clipping).
bool inFrustum(vec4 c[8]) {
  uint allOut = 63u;  // one bit per plane: left, right, top, bottom, far, near
  for (int i = 0; i < 8; ++i) {
    uint out_ = (c[i].x < -c[i].w ? 1u : 0u) | (c[i].x > c[i].w ? 2u : 0u) | (c[i].y < -c[i].w ? 4u : 0u) |
                (c[i].y > c[i].w ? 8u : 0u) | (c[i].z < 0.0 ? 16u : 0u)  // reversed depth: far plane at 0
                | (c[i].z > c[i].w ? 32u : 0u);
    allOut &= out_;
  }
  return allOut == 0u;
}

// True when every pixel the box may cover holds something strictly nearer
// than the box's nearest point.
bool occluded(vec4 c[8]) {
  vec2 lo = vec2(1e30), hi = vec2(-1e30);
  float nearest = 0.0;
  for (int i = 0; i < 8; ++i) {
    if (c[i].w <= 1e-6) return false;  // crosses the camera plane: no safe rectangle
    vec3 ndc = c[i].xyz / c[i].w;
    lo = min(lo, ndc.xy);
    hi = max(hi, ndc.xy);
    nearest = max(nearest, ndc.z);
  }
  vec2 size = vec2(pc.params.zw);
  // Pixels whose centre or samples the box may touch, one pixel of margin for rounding.
  ivec2 p0 = clamp(ivec2(floor((lo * 0.5 + 0.5) * size)) - 1, ivec2(0), ivec2(size) - 1);
  ivec2 p1 = clamp(ivec2(floor((hi * 0.5 + 0.5) * size)) + 1, ivec2(0), ivec2(size) - 1);
  int level = 0;
  while (max((p1.x >> level) - (p0.x >> level), (p1.y >> level) - (p0.y >> level)) > 1) ++level;
  float farthest = 1.0;
  for (int y = p0.y >> level; y <= (p1.y >> level); ++y)
    for (int x = p0.x >> level; x <= (p1.x >> level); ++x)
      farthest = min(farthest, texelFetch(pyramid, ivec2(x, y), level).r);
  return nearest * (1.0 + 1e-5) < farthest;
}

void main() {
  uint pos = gl_GlobalInvocationID.x;
  if (pos >= pc.params.x) return;
  Record r = records[pos];
  uint slot = r.info.x;
  mat4 m = pc.viewProj * instances[slot].model;
  vec4 c[8];
  for (int i = 0; i < 8; ++i)
    c[i] = m * vec4((i & 1) != 0 ? r.hi.x : r.lo.x, (i & 2) != 0 ? r.hi.y : r.lo.y,
                    (i & 4) != 0 ? r.hi.z : r.lo.z, 1.0);
  bool inside = inFrustum(c);
  if (pc.params.y == 0u) {
    early[pos] = Command(r.info.y, inside && visible[slot] != 0u ? 1u : 0u, r.info.z, int(r.info.w), pos);
    return;
  }
  bool seen = inside && !occluded(c);
  if (pc.params.y == 2u) {
    visible[slot] = seen ? 1u : 0u;
    return;
  }
  bool drawnEarly = early[pos].instanceCount != 0u;
  late[pos] = Command(r.info.y, seen && !drawnEarly ? 1u : 0u, r.info.z, int(r.info.w), pos);
}
