// Specular image-based lighting: the environment's radiance prefiltered by
// GGX roughness (Environment::prefiltered(): kLevels lat-long levels stacked
// vertically, the path tracer's convention), plus the emitters' ambient
// term, which has no direction. Needs common.glsl and brdf.glsl (PI).

const float ENVIRONMENT_LEVELS = 5.0;
const float ENVIRONMENT_HEIGHT = 32.0;  // texels per level

vec3 environmentLevel(vec2 uv, float level) {
  // Stay inside the level: bilinear lookups must not reach the next one.
  float v = clamp(uv.y, 0.5 / ENVIRONMENT_HEIGHT, 1.0 - 0.5 / ENVIRONMENT_HEIGHT);
  return texture(environmentMap, vec2(uv.x, (level + v) / ENVIRONMENT_LEVELS)).rgb;
}

vec2 environmentUv(vec3 d) { return vec2(atan(d.x, -d.z) / (2.0 * PI) + 0.5, acos(clamp(d.y, -1.0, 1.0)) / PI); }

// The environment itself along d, as a mirror shows it where nothing is in the way.
vec3 environmentRadiance(vec3 d) { return environmentLevel(environmentUv(d), 0.0); }

vec3 prefilteredRadiance(vec3 d, float roughness) {
  vec2 uv = environmentUv(d);
  float level = clamp(roughness, 0.0, 1.0) * (ENVIRONMENT_LEVELS - 1.0);
  float below = floor(level);
  vec3 a = environmentLevel(uv, below);
  vec3 b = environmentLevel(uv, min(below + 1.0, ENVIRONMENT_LEVELS - 1.0));
  return mix(a, b, level - below) + frame.emitterAmbient.rgb;
}
