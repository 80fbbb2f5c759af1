// The rasterizer's homogeneous medium (docs/volumes.md, "In the
// rasterizer"): along a view segment of length t, transmittance
// T = exp(-sigma_t t), plus light scattered once towards the viewer and
// emission, integrated analytically over MEDIUM_STEPS equal pieces, the
// in-scattered radiance held at its value at each piece's middle. Needs
// common.glsl, brdf.glsl, lights.glsl and a bool SHADOWS (the shadow maps
// hold the lights' visibility).

const int MEDIUM_STEPS = 4;

float henyeyGreenstein(float cosTheta, float g) {
  float d = 1.0 + g * g - 2.0 * g * cosTheta;
  return (1.0 - g * g) / (4.0 * PI * d * sqrt(d));
}

// Radiance a scattering event at p sends towards wo, per unit albedo: the
// ambient term (the average radiance around p; any phase function
// integrates it to itself) plus every light through the phase function.
// Lights with a shadow map are shadowed by one tap; the ambient term is not.
vec3 inscattered(vec3 p, vec3 wo, float g) {
  vec3 l = frame.ambient.rgb;
  for (uint i = 0u; i < frame.counts.x; ++i) {
    vec3 wi;
    vec3 li;
    if (!lightAt(i, p, wi, li)) continue;
    float v = SHADOWS && lights[i].direction.w >= 0.0 ? shadowTap(i, p) : 1.0;
    l += li * (v * henyeyGreenstein(dot(-wi, wo), g));
  }
  return l;
}

// (1 - T) / sigma_t per channel, t where sigma_t is zero.
vec3 segmentWeight(vec3 sigmaT, vec3 transmittance, float t) {
  return vec3(sigmaT.r > 1e-6 ? (1.0 - transmittance.r) / sigmaT.r : t,
              sigmaT.g > 1e-6 ? (1.0 - transmittance.g) / sigmaT.g : t,
              sigmaT.b > 1e-6 ? (1.0 - transmittance.b) / sigmaT.b : t);
}

// Light a segment from `from` towards the viewer at `to` adds, and its
// transmittance (out).
vec3 mediumSegment(vec3 from, vec3 to, vec3 sigmaA, vec3 sigmaS, vec3 emission, float g, out vec3 transmittance) {
  vec3 d = to - from;
  float t = length(d);
  vec3 sigmaT = sigmaA + sigmaS;
  transmittance = exp(-sigmaT * t);
  if (!(t > 0.0)) return vec3(0.0);
  vec3 wo = d / t;
  vec3 added = emission * segmentWeight(sigmaT, transmittance, t);
  if (any(greaterThan(sigmaS, vec3(0.0)))) {
    // Piece k spans [k, k + 1] t / N from the viewer: its light reaches the
    // viewer through T(k t / N) and adds sigma_s L (1 - T(t / N)) / sigma_t.
    float step = t / float(MEDIUM_STEPS);
    vec3 piece = segmentWeight(sigmaT, exp(-sigmaT * step), step);
    for (int k = 0; k < MEDIUM_STEPS; ++k) {
      vec3 p = to - wo * ((float(k) + 0.5) * step);
      added += exp(-sigmaT * (float(k) * step)) * piece * sigmaS * inscattered(p, wo, g);
    }
  }
  return added;
}

// The scene's fog between the camera and p, applied to the radiance p sends.
vec3 fogged(vec3 radiance, vec3 p) {
  vec3 transmittance;
  vec3 added = mediumSegment(p, frame.cameraPos.xyz, frame.fogAbsorption.rgb, frame.fogScattering.rgb,
                             frame.fogEmission.rgb, frame.fogAbsorption.w, transmittance);
  return radiance * transmittance + added;
}
