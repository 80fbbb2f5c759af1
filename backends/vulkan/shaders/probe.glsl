// Reflection-probe lookups (src/reflections/reflection_probe.cpp draws the faces,
// src/reflections/probe_prefilter.cpp prefilters them by roughness). Mirrors
// and glass follow a ray through a probe's distances (probeTraced); rough
// reflections follow it to the bounds' box and look up the scene's probe
// from its centre towards that hit (box-projected, "parallax-corrected"
// cube mapping), which is exact for a room whose walls are its bounds.
// Needs common.glsl.

bool hasProbe() { return frame.probeCentre.w > 0.0; }  // w < 0: the faces are being drawn
// The probe is also seen in rough reflections.
bool hasRoughProbe() { return frame.probeCentre.w > 1.5; }

const float PROBE_LEVELS = 4.0;      // ProbeLevels::kLevels
const float PROBE_LEVEL_SIZE = 16.0; // ProbeLevels::kSize

// How far the ray from p along dir runs to leave the scene's bounds; false
// when p is outside them.
bool boundsExit(vec3 p, vec3 dir, out float t) {
  vec3 lo = frame.sceneMin.xyz, hi = frame.sceneMax.xyz;
  t = 0.0;
  if (!(all(greaterThanEqual(p, lo)) && all(lessThanEqual(p, hi)))) return false;
  vec3 safe = vec3(abs(dir.x) > 1e-6 ? dir.x : 1e-6, abs(dir.y) > 1e-6 ? dir.y : 1e-6,
                   abs(dir.z) > 1e-6 ? dir.z : 1e-6);
  vec3 far = max((hi - p) / safe, (lo - p) / safe);
  t = max(min(far.x, min(far.y, far.z)), 0.0);
  return true;
}

vec3 boxProjected(vec3 p, vec3 dir) {
  float t;
  return boundsExit(p, dir, t) ? p + dir * t - frame.probeCentre.xyz : dir;
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

// While the faces are drawn, their alpha holds each texel's distance from
// the probe's centre over the scene's diagonal (probeDistanceAlpha: relative
// precision near the centre, also in half floats); the background keeps
// the clear alpha, -1 (probeBackground).
bool drawingProbeFaces() { return frame.probeCentre.w < -0.5; }
float probeScale() { return max(length(frame.sceneMax.xyz - frame.sceneMin.xyz), 1e-6); }
float probeDistanceAlpha(vec3 p) { return length(p - frame.cameraPos.xyz) / probeScale(); }
bool probeBackground(float alpha) { return alpha < -0.5; }

// The probe a mirror or glass instance reflects: its own, drawn from its
// box's centre (1 + k for frame.objectProbes[k]), else the scene's (0), else
// none (-1).
int instanceProbe(uint slot) {
  for (int k = 0; k < 4; ++k)
    if (frame.objectProbes[k].w > 0.0 && frame.objectProbeSlots[k] == slot) return k + 1;
  return hasProbe() ? 0 : -1;
}

vec3 probeCentreOf(int probe) { return probe == 0 ? frame.probeCentre.xyz : frame.objectProbes[probe - 1].xyz; }

// Distance from a probe's centre to what it saw towards d (nearest texel:
// filtering would blend a silhouette's near and far sides); background far.
float probeDistance(int probe, vec3 d) {
  float layer;
  vec2 uv = probeFace(d, layer);
  ivec2 texel = clamp(ivec2(uv * 128.0), ivec2(0), ivec2(127));
  float a = texelFetch(reflectionProbe, ivec3(texel, int(layer) + 6 * probe), 0).a;
  return probeBackground(a) ? 1e30 : a * probeScale();
}

// Where the ray from p along dir meets what the probe saw, as a direction
// from its centre (Szirmay-Kalos et al. 2005, "Approximate ray-tracing on
// the GPU with distance impostors"): eight steps along the ray to the
// bounds' box until a point lies beyond the surface the probe saw in its
// direction, then false position between the last two points (sixteen
// steps and four refinements gave the same builtin:cornell). Exact
// for what the centre sees; a ray passing behind something the centre
// sees in front of it stops there. Without a crossing, the box's point.
vec3 probeTraced(int probe, vec3 p, vec3 dir) {
  float end;
  if (!boundsExit(p, dir, end)) return dir;
  vec3 c = probeCentreOf(probe);
  const int STEPS = 8, REFINE = 3;
  float t0 = 0.0;
  float f0 = length(p - c) - probeDistance(probe, p - c);
  for (int i = 1; i <= STEPS; ++i) {
    float t1 = end * float(i) / float(STEPS);
    vec3 d1 = p + dir * t1 - c;
    float f1 = length(d1) - probeDistance(probe, d1);
    if (f0 < 0.0 && f1 >= 0.0) {
      // Refine by false position: the surface between t0 and t1.
      for (int k = 0; k < REFINE; ++k) {
        float t = t0 + (t1 - t0) * f0 / (f0 - f1);
        vec3 d = p + dir * t - c;
        float f = length(d) - probeDistance(probe, d);
        if (f < 0.0) {
          t0 = t;
          f0 = f;
        } else {
          t1 = t;
          f1 = f;
        }
      }
      return p + dir * (t0 + (t1 - t0) * f0 / (f0 - f1)) - c;
    }
    t0 = t1;
    f0 = f1;
  }
  return p + dir * end - c;
}

// What probe `probe` (instanceProbe) shows along dir from p; its alpha
// tells the background (probeBackground), which the caller fills.
vec4 probeSample(int probe, vec3 p, vec3 dir) {
  float layer;
  vec2 uv = probeFace(probeTraced(probe, p, dir), layer);
  return texture(reflectionProbe, vec3(clamp(uv, vec2(0.5 / 128.0), vec2(1.0 - 0.5 / 128.0)), layer + 6.0 * float(probe)));
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
