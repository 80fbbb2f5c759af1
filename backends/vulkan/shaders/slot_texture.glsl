// Material textures, filtered trilinearly over their mip chains at a level
// of detail made without implicit derivatives: lavapipe's are wrong on
// pixels along triangle edges (its helper pixels), which drew every edge of
// a minified texture as a dotted seam. The footprint is a ray cone's
// (Akenine-Moller et al., "Texture Level of Detail Strategies for Real-Time
// Ray Tracing", Ray Tracing Gems ch. 20) with one uv density a mesh: the
// pixel's size at the point times the mesh's mean uv units a length unit
// (Instance.positionScale.w) in world units, widened at a slant by the square root of the
// stretch: a filter as wide as the footprint's area rather than its long
// axis, sharper at a slant, as the converged path tracer is (seen error on
// the suite's textures scene 0.005 against 0.009 with the long axis).
// Fragment shaders only; after common.glsl.

// uv units one pixel spans at world point p, whose face's normal is n (any
// length) and whose interpolated normal is `normal` (the model's cofactor
// times a unit normal: its length is how much the transform scales the
// face's area; zero for a mesh without normals).
float uvFootprint(Instance inst, vec3 p, vec3 n, vec3 normal) {
  float side = (frame.viewProj * vec4(p, 1.0)).w * max(frame.viewport.z, frame.viewport.w);
  // Seen at a slant the footprint stretches (counted up to eight times, near
  // 83 degrees); no face or no distance counts as face-on.
  vec3 toEye = frame.cameraPos.xyz - p;
  float across = length(n) * length(toEye);
  float slope = across > 0.0 ? clamp(abs(dot(n, toEye)) / across, 0.125, 1.0) : 1.0;
  // The mesh's density in world units: over the scale of the face's area,
  // else the transform's mean scale (a longest axis when it is flat).
  float area = length(normal);
  if (!(area > 1e-12)) {
    mat3 model = mat3(inst.model);
    float volume = abs(determinant(model));
    float longest = max(length(model[0]), max(length(model[1]), length(model[2])));
    area = volume > 0.0 ? pow(volume, 2.0 / 3.0) : longest * longest;
  }
  return area > 0.0 ? inst.positionScale.w * side / (sqrt(area) * sqrt(slope)) : 0.0;
}

// A material texture at its slot's uv, for a pixel spanning `footprint` uv units.
vec4 slotTexture(sampler2D tex, uint material, int slot, vec2 uv, float footprint) {
  vec3 row0 = materials[material].uv[2 * slot].xyz, row1 = materials[material].uv[2 * slot + 1].xyz;
  // KHR_texture_transform's scale changes the texels a uv unit holds.
  float stretch = sqrt(abs(row0.x * row1.y - row0.y * row1.x));
  vec2 size = vec2(textureSize(tex, 0));
  float texels = footprint * stretch * sqrt(size.x * size.y);
  return textureLod(tex, slotUv(material, slot, uv), log2(max(texels, 1e-8)));
}
