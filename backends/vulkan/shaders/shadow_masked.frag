#version 450
#include "common.glsl"

// Where mesh.frag discards a MASK material's fragment, the light passes too.
layout(set = 1, binding = 0) uniform sampler2D baseColorTex;

layout(location = 0) in vec2 uv;

void main() {
  Material m = materials[pc.material];
  if (m.baseColor.a * textureLod(baseColorTex, slotUv(pc.material, BASE_COLOR_SLOT, uv), 0.0).a < m.pbr.w) discard;
}
