// Reflection-probe lookups (src/reflections/reflection_probe.cpp draws the faces,
// src/reflections/probe_prefilter.cpp prefilters them by roughness). A
// direction from a point inside the scene's bounds is first followed to
// the bounds' box and looked up from the probe's centre towards that hit
// (box-projected, "parallax-corrected" cube mapping), which is exact for a
// room whose walls are its bounds. Needs common.glsl.

bool hasProbe() { return frame.probeCentre.w > 0.0; }
// The probe is also seen in rough reflections.
bool hasRoughProbe() { return frame.probeCentre.w > 1.5; }

const float PROBE_LEVELS = 4.0;      // ProbeLevels::kLevels
const float PROBE_LEVEL_SIZE = 16.0; // ProbeLevels::kSize

vec3 boxProjected(vec3 p, vec3 dir) {
  vec3 lo = frame.sceneMin.xyz, hi = frame.sceneMax.xyz;
  if (!(all(greaterThanEqual(p, lo)) && all(lessThanEqual(p, hi)))) return dir;
  vec3 safe = vec3(abs(dir.x) > 1e-6 ? dir.x : 1e-6, abs(dir.y) > 1e-6 ? dir.y : 1e-6,
                   abs(dir.z) > 1e-6 ? dir.z : 1e-6);
  vec3 far = max((hi - p) / safe, (lo - p) / safe);
  float t = min(far.x, min(far.y, far.z));
  return p + dir * max(t, 0.0) - frame.probeCentre.xyz;
}

// The face of d's major axis (its layer) and the position on it, with the
// forward and up it was drawn with (kProbeFaceForward, kProbeFaceUp).
vec2 probeFace(vec3 d, out float layer) {
  vec3 a = abs(d);
  vec3 forward, up;
  if (a.x >= a.y && a.x >= a.z) {
    layer = d.x > 0.0 ? 0.0 : 1.0;
    forward = vec3(sign(d.x), 0.0, 0.0);
    up = vec3(0.0, 1.0, 0.0);
  } else if (a.y >= a.z) {
    layer = d.y > 0.0 ? 2.0 : 3.0;
    forward = vec3(0.0, sign(d.y), 0.0);
    up = vec3(0.0, 0.0, sign(d.y));
  } else {
    layer = d.z > 0.0 ? 4.0 : 5.0;
    forward = vec3(0.0, 0.0, sign(d.z));
    up = vec3(0.0, 1.0, 0.0);
  }
  vec3 right = cross(forward, up);
  float w = dot(d, forward);
  return vec2(0.5 + 0.5 * dot(d, right) / w, 0.5 - 0.5 * dot(d, up) / w);
}

vec3 probeRadiance(vec3 p, vec3 dir) {
  float layer;
  vec2 uv = probeFace(boxProjected(p, dir), layer);
  return texture(reflectionProbe, vec3(clamp(uv, vec2(0.5 / 128.0), vec2(1.0 - 0.5 / 128.0)), layer)).rgb;
}

// Level k >= 1 of the rough levels: faces stacked vertically, level-major.
vec3 probeLevel(vec2 uv, float layer, float k) {
  vec2 st = clamp(uv, vec2(0.5 / PROBE_LEVEL_SIZE), vec2(1.0 - 0.5 / PROBE_LEVEL_SIZE));
  return texture(probeLevels, vec2(st.x, ((k - 1.0) * 6.0 + layer + st.y) / (6.0 * PROBE_LEVELS))).rgb;
}

// The probe around the mirror direction, prefiltered by GGX roughness:
// level 0 is the probe itself.
vec3 probePrefiltered(vec3 p, vec3 dir, float roughness) {
  float layer;
  vec2 uv = probeFace(boxProjected(p, dir), layer);
  float level = clamp(roughness, 0.0, 1.0) * PROBE_LEVELS;
  float below = floor(level);
  vec3 a = below < 0.5 ? texture(reflectionProbe, vec3(clamp(uv, vec2(0.5 / 128.0), vec2(1.0 - 0.5 / 128.0)),
                                                       layer)).rgb
                       : probeLevel(uv, layer, below);
  vec3 b = probeLevel(uv, layer, min(below + 1.0, PROBE_LEVELS));
  return mix(a, b, level - below);
}
