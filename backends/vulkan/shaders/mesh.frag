#version 450
#include "common.glsl"
#include "slot_texture.glsl"
#include "brdf.glsl"
#include "lights.glsl"
#include "environment.glsl"
#include "probe.glsl"
#include "probe_volume.glsl"

// Direct light from point, spot and directional lights and from emissive
// geometry's patches (area-like lights) with the Embree back-end's BSDFs
// (f * cos, same units), an ambient term from the average environment
// radiance, and emission from the front face.

// Specialised per material class: CPU rasterizers execute both sides of
// branches, so unused BSDFs, texture fetches and shadow taps must be compiled out.
layout(constant_id = 0) const uint MATERIAL_TYPE = 0u;
layout(constant_id = 1) const bool BASE_TEXTURE = false;
layout(constant_id = 2) const bool EMISSION_TEXTURE = false;
layout(constant_id = 3) const bool SHADOWS = false;
layout(constant_id = 4) const bool FOG = false;  // the environment has a medium
layout(constant_id = 5) const bool NORMAL_TEXTURE = false;
layout(constant_id = 6) const bool METALLIC_ROUGHNESS_TEXTURE = false;
layout(constant_id = 7) const bool OCCLUSION_TEXTURE = false;
layout(constant_id = 8) const bool UNLIT = false;  // lines and points: no surface to light

#include "medium.glsl"

layout(set = 1, binding = 0) uniform sampler2D baseColorTex;
layout(set = 1, binding = 1) uniform sampler2D emissionTex;
layout(set = 1, binding = 2) uniform sampler2D metallicRoughnessTex;
layout(set = 1, binding = 3) uniform sampler2D normalTex;
layout(set = 1, binding = 4) uniform sampler2D occlusionTex;

layout(location = 0) in vec3 worldPos;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec2 uv;
layout(location = 3) flat in uint instanceSlot;

layout(location = 0) out vec4 outColour;

const uint DIFFUSE = 0u, CONDUCTOR = 1u, DIELECTRIC = 2u, MIRROR = 3u, GLASS = 4u, METALLIC_ROUGHNESS = 5u;

// The split-sum table at n.v = c (brdf_table.hpp): x, y = A, B of the
// directional albedo F0 A + B; z = the albedo with F = 1 averaged over the
// hemisphere (cosine-weighted), the same for every c of a roughness.
vec3 brdfTableAt(float c, float roughness) {
  vec2 st = clamp(vec2(c, roughness), vec2(1.0 / 64.0), vec2(63.0 / 64.0));  // texel centres of the 32x32 table
  return texture(brdfTable, st).xyz;
}

// Kulla and Conty's multiple scattering of a metal, f_ms * cos(wi), as the
// path tracer's BSDF adds it: the energy single-scattering GGX loses towards
// wo and towards wi, tinted by the average Fresnel. At roughness 1 it is more
// than half of what a white metal reflects of a light.
vec3 metalMultipleScattering(vec3 colour, float roughness, float co, float ci) {
  vec3 o = brdfTableAt(co, roughness), i = brdfTableAt(ci, roughness);
  float eavg = o.z;
  vec3 favg = colour + (vec3(1.0) - colour) / 21.0;
  vec3 fms = favg * favg * eavg / (vec3(1.0) - favg * (1.0 - eavg));
  return fms * ((1.0 - (o.x + o.y)) * (1.0 - (i.x + i.y)) * ci / (PI * max(1e-4, 1.0 - eavg)));
}

// f * |cos(wi)| for unit vectors; n is the shading normal on wo's side.
// metallic is read by METALLIC_ROUGHNESS only. Without `specular`, the
// glossy reflection is left out (the diffuse part and transmission stay).
vec3 evalBsdf(uint type, vec3 colour, float alpha, float metallic, float eta, vec3 n, vec3 wo, vec3 wi, bool specular) {
  float co = dot(n, wo);
  float ci = dot(n, wi);
  if (type == DIFFUSE) return ci > 0.0 ? colour * (ci / PI) : vec3(0.0);
  if (!specular && ci > 0.0 && type != METALLIC_ROUGHNESS) return vec3(0.0);
  if (type == METALLIC_ROUGHNESS) {
    // glTF appendix B: mix(dielectric, metal, metallic) with
    // dielectric = mix(diffuse, specular, F(0.04)) and metal = specular F(colour).
    if (ci <= 0.0) return vec3(0.0);
    vec3 h = normalize(wo + wi);
    float m = 1.0 - clamp(dot(wo, h), 0.0, 1.0);
    float fc = (m * m) * (m * m) * m;
    vec3 f0 = mix(vec3(0.04), colour, metallic);
    vec3 glossy = (f0 + (1.0 - f0) * fc) * (ggxD(dot(n, h), alpha) * ggxG2(co, ci, alpha) / (4.0 * co));
    if (metallic > 0.0) glossy += metallic * metalMultipleScattering(colour, sqrt(alpha), co, ci);
    float diffuseWeight = (1.0 - metallic) * (1.0 - (0.04 + 0.96 * fc));
    return (specular ? glossy : vec3(0.0)) + colour * (diffuseWeight * ci / PI);
  }
  if (type == CONDUCTOR) {
    if (ci <= 0.0) return vec3(0.0);
    vec3 h = normalize(wo + wi);
    return schlick(colour, dot(wo, h)) * (ggxD(dot(n, h), alpha) * ggxG2(co, ci, alpha) / (4.0 * co));
  }
  if (type == DIELECTRIC) {
    if (ci > 0.0) {
      vec3 h = normalize(wo + wi);
      float f = fresnelDielectric(dot(wo, h), eta);
      return vec3(f * ggxD(dot(n, h), alpha) * ggxG2(co, ci, alpha) / (4.0 * co));
    }
    if (ci == 0.0) return vec3(0.0);
    vec3 h = wo + eta * wi;
    if (dot(h, h) <= 0.0) return vec3(0.0);
    h = normalize(h);
    if (dot(n, h) < 0.0) h = -h;
    float oh = dot(wo, h);
    float ih = dot(wi, h);
    if (oh <= 0.0 || ih >= 0.0) return vec3(0.0);
    float f = fresnelDielectric(oh, eta);
    float denom = oh + eta * ih;
    return colour * ((1.0 - f) * ggxD(dot(n, h), alpha) * ggxG2(co, ci, alpha) * eta * eta * abs(ih) * oh /
                     (co * denom * denom));
  }
  return vec3(0.0);  // Mirror and Glass are delta BSDFs: no direct light from point-like lights
}

// The shading normal n bent by the normal map: a tangent frame from the
// screen-space derivatives of position and uv (Schüler's cotangent frame),
// x along +u and y along -v (glTF: +y is up in the image, v runs down).
// A bent normal that would face away from the viewer is pulled back to the
// silhouette plane.
// The uv derivatives are taken before the texture transform (rows) and
// mapped through it: lavapipe gives values loaded from a buffer no
// derivatives.
vec3 normalMapped(vec3 n, vec3 wo, float scale, vec3 row0, vec3 row1, float footprint) {
  vec3 dp1 = dFdx(worldPos), dp2 = dFdy(worldPos);
  mat2 linear = mat2(row0.x, row1.x, row0.y, row1.y);
  vec2 duv1 = linear * dFdx(uv), duv2 = linear * dFdy(uv);
  vec3 dp2perp = cross(dp2, n), dp1perp = cross(n, dp1);
  vec3 t = dp2perp * duv1.x + dp1perp * duv2.x;
  vec3 b = dp2perp * duv1.y + dp1perp * duv2.y;
  float len2 = max(dot(t, t), dot(b, b));
  if (!(len2 > 0.0)) return n;  // no uv gradient: nothing to bend along
  // The derivation assumes (dp1, dp2, n) right-handed; Vulkan's y-down
  // framebuffer makes it left-handed for faces seen from the front.
  float inv = inversesqrt(len2) * (dot(cross(dp1, dp2), n) < 0.0 ? -1.0 : 1.0);
  vec3 ts = slotTexture(normalTex, pc.material, NORMAL_SLOT, uv, footprint).xyz * 2.0 - 1.0;
  ts.xy *= scale;
  vec3 bent = normalize(t * (inv * ts.x) - b * (inv * ts.y) + n * ts.z);
  float c = dot(bent, wo);
  return c > 1e-3 ? bent : normalize(bent + wo * (1e-3 - c));
}

// Directional albedo of the metallic-roughness BRDF at n.v = c, from the
// split-sum table (F0 A + B), with Fdez-Aguera's multiple-scattering
// compensation (the energy single-scattering GGX loses, 1 - (A + B), given
// back in proportion to F0), and Lambert diffuse taking what the dielectric
// specular leaves: a white material reflects all of a uniform environment.
// The specular part is returned in `specular`, the diffuse part as result.
vec3 metallicRoughnessAlbedo(vec3 colour, float metallic, float roughness, float c, out vec3 specular) {
  vec2 ab = brdfTableAt(c, roughness).xy;
  float single = ab.x + ab.y;
  vec3 f0 = mix(vec3(0.04), colour, metallic);
  specular = (f0 * ab.x + ab.y) * (1.0 + f0 * (1.0 - single) / single);
  float dielectricSpecular = (0.04 * ab.x + ab.y) * (1.0 + 0.04 * (1.0 - single) / single);
  return colour * ((1.0 - metallic) * (1.0 - dielectricSpecular));
}

// Fraction of 3x3 shadow-map taps that see p lit. Lights are read field by
// field: copying the whole struct (with its matrix) per fragment is costly
// on CPU rasterizers.
float visibility(uint i, vec3 p, vec3 ng) {
  float offset = lights[i].cone.z;
  if (uint(lights[i].position.w) != DIRECTIONAL) offset *= length(lights[i].position.xyz - p);
  vec4 c = lights[i].shadowMatrix * vec4(p + ng * offset, 1.0);
  if (c.w <= 0.0) return 1.0;
  vec3 s = c.xyz / c.w;
  vec2 st = s.xy * 0.5 + 0.5;
  if (any(lessThan(st, vec2(0.0))) || any(greaterThan(st, vec2(1.0))) || s.z < 0.0 || s.z > 1.0) return 1.0;
  float texel = lights[i].cone.w;
  float layer = lights[i].direction.w;
  float sum = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) sum += texture(shadowMaps, vec4(st + vec2(x, y) * texel, layer, s.z));
  return sum / 9.0;
}

// Where light refracted into a closed glass object at p, along dir, leaves
// it and which way it goes on: through the ellipsoid inscribed in the
// mesh's box (exact for a ball), refracted out at the far side, or
// reflected back in where it cannot leave (total internal reflection; no
// further bounce is followed). False for a flat mesh (a pane has no far
// side) or a ray that misses the ellipsoid: then the light goes on as it
// entered.
bool throughGlass(vec3 p, vec3 dir, float ior, inout vec3 from, inout vec3 along) {
  Instance inst = instances[instanceSlot];
  vec3 semi = 0.5 * inst.positionScale.xyz;
  if (min(semi.x, min(semi.y, semi.z)) <= 1e-4 * max(semi.x, max(semi.y, semi.z))) return false;
  mat3 model = mat3(inst.model);
  // A transform flat along some axis (a scale of 0) has no inside to cross.
  if (!(abs(determinant(model)) > 1e-6 * length(model[0]) * length(model[1]) * length(model[2]))) return false;
  mat3 toObject = inverse(model);
  vec3 centre = inst.positionOffset.xyz + semi;
  vec3 q = (toObject * (p - inst.model[3].xyz) - centre) / semi;
  vec3 d = (toObject * dir) / semi;
  float a = dot(d, d), b = dot(q, d), c = dot(q, q) - 1.0;
  float disc = b * b - a * c;
  if (!(a > 0.0) || disc < 0.0) return false;
  float t = (-b + sqrt(disc)) / a;
  if (!(t > 0.0)) return false;
  vec3 e = q + t * d;
  vec3 outward = normalize(transpose(toObject) * (e / semi));
  vec3 leaving = refract(dir, -outward, ior);
  from = (inst.model * vec4(centre + e * semi, 1.0)).xyz;
  along = dot(leaving, leaving) > 0.0 ? leaving : reflect(dir, -outward);
  return true;
}

// What a mirror or glass sees along dir from p through its probe: the
// environment where the probe saw background (in fog, the fog's colour the
// background was cleared to).
vec3 probeRadiance(int probe, vec3 p, vec3 dir) {
  vec4 seen = probeSample(probe, p, dir);
  return probeBackground(seen.a) && !FOG ? environmentRadiance(dir) : seen.rgb;
}

void main() {
  Material m = materials[pc.material];
  const uint type = MATERIAL_TYPE;
  vec3 base = m.baseColor.rgb;
  float opacity = m.baseColor.a;
  // The face's normal (unnormalised), taken where every pixel of the quad
  // still runs (before any discard).
  vec3 faceCross = cross(dFdx(worldPos), dFdy(worldPos));
  const bool textured = BASE_TEXTURE || EMISSION_TEXTURE || METALLIC_ROUGHNESS_TEXTURE || NORMAL_TEXTURE ||
                        OCCLUSION_TEXTURE;
  float footprint = 0.0;
  if (textured)
    footprint = uvFootprint(instances[instanceSlot], worldPos, length(worldNormal) > 1e-8 ? worldNormal : faceCross,
                            worldNormal);
  if (BASE_TEXTURE) {
    vec4 t = slotTexture(baseColorTex, pc.material, BASE_COLOR_SLOT, uv, footprint);
    base *= t.rgb;
    // MASK cuts at the first level's alpha, as the shadow pass does: alpha
    // averaged down the chain would thin foliage away in the distance.
    opacity *= m.pbr.w > 0.0 ? textureLod(baseColorTex, slotUv(pc.material, BASE_COLOR_SLOT, uv), 0.0).a : t.a;
  }
  if (m.pbr.w > 0.0) {  // glTF MASK: cut away below the cut-off, opaque above
    if (opacity < m.pbr.w) discard;
    opacity = 1.0;
  }
  if (UNLIT) {  // their colour as it is, as glTF viewers draw lines and points
    vec3 e = m.emission.rgb;
    if (EMISSION_TEXTURE) e *= slotTexture(emissionTex, pc.material, EMISSION_SLOT, uv, footprint).rgb;
    outColour = vec4(FOG ? fogged(base + e, worldPos) : base + e, opacity);
    if (drawingProbeFaces()) outColour.a = probeDistanceAlpha(worldPos);
    return;
  }

  vec3 wo = normalize(frame.cameraPos.xyz - worldPos);
  // Flat face normal, turned towards the viewer.
  vec3 ng = normalize(faceCross);
  if (dot(ng, wo) < 0.0) ng = -ng;
  // As in the path tracer, the shading normal is flipped to the side of the
  // face (by winding) that the viewer sees.
  float len = length(worldNormal);
  vec3 n = len > 1e-8 ? (gl_FrontFacing ? worldNormal : -worldNormal) / len : ng;
  if (NORMAL_TEXTURE)
    n = normalMapped(n, wo, m.pbr.z, m.uv[2 * NORMAL_SLOT].xyz, m.uv[2 * NORMAL_SLOT + 1].xyz, footprint);
  float eta = gl_FrontFacing ? m.params.y : 1.0 / m.params.y;
  float alpha = m.params.x;
  float roughness = m.pbr.x;
  float metallic = m.pbr.y;
  if (METALLIC_ROUGHNESS_TEXTURE) {
    vec4 t = slotTexture(metallicRoughnessTex, pc.material, METALLIC_ROUGHNESS_SLOT, uv, footprint);
    roughness *= t.g;
    metallic *= t.b;
    alpha = max(1e-3, roughness * roughness);
  }
  float co = dot(n, wo);

  // Emissive surfaces are in the probe: where rough reflections read it,
  // their patch lights add no glossy reflection of their own (that would
  // count them twice).
  const bool probeLit = hasRoughProbe();
  vec3 radiance = vec3(0.0);
  if (co > 1e-6) {
    for (uint i = 0u; i < frame.counts.x; ++i) {
      vec3 wi;
      vec3 li;
      if (!lightAt(i, worldPos, wi, li)) continue;
      // Shading and geometric normal must agree on the side of wi.
      if ((dot(wi, ng) > 0.0) != (dot(wi, n) > 0.0)) continue;
      bool specular = !(probeLit && uint(lights[i].position.w) == EMITTER);
      vec3 f = evalBsdf(type, base, alpha, metallic, eta, n, wo, wi, specular);
      if (max(f.r, max(f.g, f.b)) <= 0.0) continue;
      float v = SHADOWS && lights[i].direction.w >= 0.0 ? visibility(i, worldPos, ng) : 1.0;
      radiance += f * li * v;
    }
  }

  // Without occlusion: diffuse reflection of the environment's average
  // radiance (exact for Lambert under a constant environment), specular
  // reflection of the environment prefiltered by roughness around the
  // mirror direction, weighted by the directional albedo. Where the probe
  // can, the specular part reflects what it sees of the scene instead.
  // (Diffuse light from the probe was tried: one probe at the centre sees
  // lit ceilings from too near and without shadows, and on the quality
  // suite its irradiance, even rescaled to the ambient's level, made 10 of
  // 14 scenes worse.)
  // With the irradiance volume, diffuse reflection reads its light instead:
  // bounced light and the environment, occluded, E / pi for Lambert.
  // (Only the material classes that reflect diffusely read it: the others
  // compile it out.)
  vec3 ambient = frame.ambient.rgb;
  vec3 irradiance;
  if ((type == METALLIC_ROUGHNESS || type == DIFFUSE) && hasVolume() && volumeIrradiance(worldPos, n, wo, irradiance))
    ambient = irradiance / PI;
  vec3 mirrored = reflect(-wo, n);
  const vec3 direct = radiance;
  if (type == METALLIC_ROUGHNESS) {
    vec3 specular;
    vec3 diffuse = metallicRoughnessAlbedo(base, metallic, roughness, max(co, 0.0), specular);
    vec3 reflected = probeLit ? probePrefiltered(worldPos, mirrored, roughness) : prefilteredRadiance(mirrored, roughness);
    radiance += diffuse * ambient + specular * reflected;
  } else if (type == DIFFUSE) {
    radiance += base * ambient;
  } else if (type == MIRROR) {
    int probe = instanceProbe(instanceSlot);
    radiance += base * (probe >= 0 ? probeRadiance(probe, worldPos, mirrored) : prefilteredRadiance(mirrored, 0.0));
  } else if (type == GLASS && instanceProbe(instanceSlot) >= 0) {
    int probe = instanceProbe(instanceSlot);
    // What the probe sees along the mirrored and the refracted direction
    // (in and out through the ellipsoid inscribed in the box), by Fresnel.
    float f = fresnelDielectric(max(co, 0.0), eta);
    vec3 refracted = refract(-wo, n, 1.0 / eta);
    vec3 from = worldPos, along = refracted;
    if (gl_FrontFacing && dot(refracted, refracted) > 0.0) throughGlass(worldPos, refracted, m.params.y, from, along);
    vec3 through = dot(refracted, refracted) > 0.0 ? probeRadiance(probe, from, along) : vec3(0.0);
    radiance += f * probeRadiance(probe, worldPos, mirrored) + (1.0 - f) * base * through;
  } else if (type == CONDUCTOR) {
    vec3 reflected = probeLit ? probePrefiltered(worldPos, mirrored, m.pbr.x) : prefilteredRadiance(mirrored, m.pbr.x);
    radiance += schlick(base, max(co, 0.0)) * reflected;
  } else {
    // Glass without a probe and rough dielectrics: the reflected and the
    // transmitted part, each blurred by roughness, what is behind seen once
    // refracted (the way out of the object is not traced), as the reflection
    // sees the probe or the environment.
    float f = fresnelDielectric(max(co, 0.0), eta);
    vec3 reflected = probeLit ? probePrefiltered(worldPos, mirrored, m.pbr.x) : prefilteredRadiance(mirrored, m.pbr.x);
    vec3 refracted = refract(-wo, n, 1.0 / eta);
    vec3 from = worldPos, along = refracted;
    if (gl_FrontFacing && dot(refracted, refracted) > 0.0) throughGlass(worldPos, refracted, m.params.y, from, along);
    vec3 behind = dot(refracted, refracted) <= 0.0 ? vec3(0.0)
                  : probeLit                      ? probePrefiltered(from, along, m.pbr.x)
                                                  : prefilteredRadiance(along, m.pbr.x);
    radiance += f * reflected + (1.0 - f) * base * behind;
  }
  // glTF's occlusion darkens this ambient and image-based part only.
  if (OCCLUSION_TEXTURE) {
    float occluded = slotTexture(occlusionTex, pc.material, OCCLUSION_SLOT, uv, footprint).r;
    radiance = direct + (1.0 + m.params.z * (occluded - 1.0)) * (radiance - direct);
  }

  if (gl_FrontFacing) {
    vec3 e = m.emission.rgb;
    if (EMISSION_TEXTURE) e *= slotTexture(emissionTex, pc.material, EMISSION_SLOT, uv, footprint).rgb;
    radiance += e;
  }
  if (FOG) radiance = fogged(radiance, worldPos);
  outColour = vec4(radiance, drawingProbeFaces() ? probeDistanceAlpha(worldPos) : opacity);
}
