// Material textures, filtered trilinearly over their mip chains at a level
// of detail made without implicit derivatives: lavapipe's are wrong on
// pixels along triangle edges (its helper pixels), which drew every edge of
// a minified texture as a dotted seam. The footprint is a ray cone's
// (Akenine-Moller et al., "Texture Level of Detail Strategies for Real-Time
// Ray Tracing", Ray Tracing Gems ch. 20) with one uv density a mesh: the
// pixel's size at the point times the mesh's mean uv units a world unit
// (Instance.positionScale.w), widened at a slant by the square root of the
// stretch: a filter as wide as the footprint's area rather than its long
// axis, sharper at a slant, as the converged path tracer is (seen error on
// the suite's textures scene 0.005 against 0.009 with the long axis).
// Fragment shaders only; after common.glsl.

// uv units one pixel spans at world point p on a face of normal n.
float uvFootprint(Instance inst, vec3 p, vec3 n) {
  vec4 c = frame.viewProj * vec4(p, 1.0);
  vec4 x = frame.invViewProj * (c + vec4(2.0 * c.w / frame.viewport.x, 0.0, 0.0, 0.0));
  vec4 y = frame.invViewProj * (c + vec4(0.0, 2.0 * c.w / frame.viewport.y, 0.0, 0.0));
  float side = max(length(x.xyz / x.w - p), length(y.xyz / y.w - p));
  // Seen at a slant the footprint stretches (counted up to eight times, near
  // 83 degrees); NaN (no face) counts as face-on.
  float slope = abs(dot(n, normalize(frame.cameraPos.xyz - p)));
  slope = slope < 0.125 ? 0.125 : (slope <= 1.0 ? slope : 1.0);
  return inst.positionScale.w * side / sqrt(slope);
}

// A material texture at its slot's uv, for a pixel spanning `footprint` uv units.
vec4 slotTexture(sampler2D tex, uint material, int slot, vec2 uv, float footprint) {
  vec3 row0 = materials[material].uv[2 * slot].xyz, row1 = materials[material].uv[2 * slot + 1].xyz;
  vec2 st = vec2(dot(row0, vec3(uv, 1.0)), dot(row1, vec3(uv, 1.0)));
  // KHR_texture_transform's scale changes the texels a uv unit holds.
  float stretch = sqrt(abs(row0.x * row1.y - row0.y * row1.x));
  vec2 size = vec2(textureSize(tex, 0));
  float texels = footprint * stretch * max(size.x, size.y);
  return textureLod(tex, st, log2(max(texels, 1e-8)));
}
