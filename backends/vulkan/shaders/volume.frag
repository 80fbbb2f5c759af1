#version 450
#include "common.glsl"
#include "brdf.glsl"
#include "lights.glsl"

// A see-through volume's front face (back faces are culled): the medium
// between here and the nearer of its back face and opaque geometry (from
// volumeBackDepth), over what lies behind, by dual-source blending
// (colour = outAdd + destination * outTransmit). The boundary reflects the
// ambient term with the dielectric Fresnel factor of its ior and refracts
// nothing: what is behind is seen straight through.

layout(constant_id = 3) const bool SHADOWS = false;
layout(constant_id = 4) const bool FOG = false;

#include "medium.glsl"

layout(location = 0) in vec3 worldPos;
layout(location = 1) in vec3 worldNormal;

layout(location = 0, index = 0) out vec4 outAdd;
layout(location = 0, index = 1) out vec4 outTransmit;

void main() {
  Material m = materials[pc.material];
  vec3 camera = frame.cameraPos.xyz;
  vec3 wo = normalize(camera - worldPos);

  // Where the view ray leaves the medium: reversed depth, 0 = nothing (an
  // open mesh over the background), which gives no thickness.
  vec3 exitPoint = worldPos;
  float back = texelFetch(volumeBackDepth, ivec2(gl_FragCoord.xy), 0).r;
  if (back > 0.0) {
    vec2 ndc = gl_FragCoord.xy / frame.viewport.xy * 2.0 - 1.0;
    vec4 q = frame.invViewProj * vec4(ndc, back, 1.0);
    vec3 p = q.xyz / q.w;
    // Only beyond this face: a back face nearer than it belongs to another volume.
    if (dot(p - worldPos, -wo) > 0.0) exitPoint = p;
  }
  vec3 transmittance;
  vec3 added = mediumSegment(exitPoint, worldPos, m.mediumAbsorption.rgb, m.mediumScattering.rgb,
                             m.mediumEmission.rgb, m.mediumAbsorption.w, transmittance);

  float len = length(worldNormal);
  vec3 n = len > 1e-8 ? worldNormal / len : normalize(cross(dFdx(worldPos), dFdy(worldPos)));
  if (dot(n, wo) < 0.0) n = -n;
  float f = fresnelDielectric(dot(n, wo), m.params.y);
  vec3 radiance = f * frame.ambient.rgb + (1.0 - f) * added;
  vec3 through = (1.0 - f) * transmittance;
  if (FOG) {
    // The destination already holds the fog in front of this face (it is
    // fogged over its whole distance): only this face's light needs it.
    vec3 fogTransmittance;
    vec3 fog = mediumSegment(worldPos, camera, frame.fogAbsorption.rgb, frame.fogScattering.rgb,
                             frame.fogEmission.rgb, frame.fogAbsorption.w, fogTransmittance);
    radiance = radiance * fogTransmittance + (1.0 - through) * fog;
  }
  float coverage = 1.0 - (through.r + through.g + through.b) / 3.0;
  outAdd = vec4(radiance, coverage);
  outTransmit = vec4(through, 1.0 - coverage);
}
