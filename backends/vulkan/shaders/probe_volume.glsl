// Diffuse light from the irradiance volume (tsr/backend/irradiance_volume.hpp;
// the path tracer fills its probes). A point reads the eight probes around
// it, weighted trilinearly, by whether it faces them, and by Chebyshev's
// test of its distance from each probe against the mean distance that probe
// saw in its direction (Majercik et al. 2019), so light does not leak
// through walls. Needs common.glsl and brdf.glsl (PI).

const uint VOLUME_FACES = 6u;          // IrradianceVolume::kFaces
const uint VOLUME_DISTANCE_SIDE = 8u;  // IrradianceVolume::kDistanceSide

bool hasVolume() { return frame.volumeMin.w > 0.5; }

// Clarberg's equal-area mapping from the sphere to the unit square
// (backend::equalAreaSphereToSquare).
vec2 equalAreaSphereToSquare(vec3 d) {
  vec3 a = abs(d);
  float r = sqrt(max(0.0, 1.0 - a.z));
  float larger = max(a.x, a.y);
  float b = larger == 0.0 ? 0.0 : min(a.x, a.y) / larger;
  float phi = atan(b) * 2.0 / PI;
  if (a.x < a.y) phi = 1.0 - phi;
  float v = phi * r, u = r - v;
  if (d.z < 0.0) {
    float t = u;
    u = 1.0 - v;
    v = 1.0 - t;
  }
  return 0.5 * (vec2(d.x < 0.0 ? -u : u, d.y < 0.0 ? -v : v) + 1.0);
}

// Mean distance and mean squared distance a probe saw towards dir (unit),
// from the texel dir falls in (bilinear filtering took the frame from 1.44
// to 1.59 times the ambient term's on lavapipe; it smooths the arcs where
// the test's verdict changes from texel to texel).
vec2 volumeDistance(uint probe, vec3 dir) {
  uvec2 t = min(uvec2(equalAreaSphereToSquare(dir) * float(VOLUME_DISTANCE_SIDE)), uvec2(VOLUME_DISTANCE_SIDE - 1u));
  uint texel = probe * VOLUME_DISTANCE_SIDE * VOLUME_DISTANCE_SIDE + t.y * VOLUME_DISTANCE_SIDE + t.x;
  vec4 pair = volumeData[frame.volumeCounts.w * VOLUME_FACES + texel / 2u];
  return (texel & 1u) == 0u ? pair.xy : pair.zw;
}

// A probe's irradiance on a surface facing n (backend::IrradianceVolume::irradianceAt):
// the three faces n points to, by the squares of n's components.
vec3 volumeProbeIrradiance(uint probe, vec3 n) {
  uint b = probe * VOLUME_FACES;
  vec3 n2 = n * n;
  return n2.x * volumeData[b + (n.x < 0.0 ? 1u : 0u)].rgb + n2.y * volumeData[b + (n.y < 0.0 ? 3u : 2u)].rgb +
         n2.z * volumeData[b + (n.z < 0.0 ? 5u : 4u)].rgb;
}

// Irradiance at p on a surface facing n, seen from wo; false where no probe
// around p can be used (all inside geometry).
bool volumeIrradiance(vec3 p, vec3 n, vec3 wo, out vec3 irradiance) {
  irradiance = vec3(0.0);
  uvec3 counts = frame.volumeCounts.xyz;
  vec3 lo = frame.volumeMin.xyz;
  vec3 cell = (frame.volumeMax.xyz - lo) / vec3(counts);
  // Read from a little in front of the surface, towards the viewer, so the
  // surface's own distance in a probe's map does not shadow it.
  vec3 biased = p + (0.2 * n + 0.8 * wo) * (0.25 * min(cell.x, min(cell.y, cell.z)));
  vec3 g = (biased - lo) / cell - 0.5;
  ivec3 last = ivec3(counts) - 1;
  ivec3 base = clamp(ivec3(floor(g)), ivec3(0), last);
  vec3 f = clamp(g - vec3(base), 0.0, 1.0);
  vec3 sum = vec3(0.0);
  float total = 0.0;
  for (int k = 0; k < 8; ++k) {
    ivec3 o = ivec3(k & 1, (k >> 1) & 1, k >> 2);
    ivec3 c = min(base + o, last);
    uint probe = uint(c.x) + counts.x * (uint(c.y) + counts.y * uint(c.z));
    if (volumeData[probe * VOLUME_FACES].w <= 0.0) continue;  // inside geometry
    vec3 at = lo + (vec3(c) + 0.5) * cell;
    // Probes behind the surface count less (not nothing: a thin room may have only those).
    float facing = 0.5 * (dot(normalize(at - p), n) + 1.0);
    float w = facing * facing + 0.2;
    vec3 fromProbe = biased - at;
    float r = length(fromProbe);
    vec2 m = volumeDistance(probe, fromProbe / max(r, 1e-6));
    if (r > m.x) {
      float variance = abs(m.y - m.x * m.x);
      float d = r - m.x;
      float chebyshev = variance / (variance + d * d);
      w *= chebyshev * chebyshev * chebyshev;
    }
    // A probe that sees nothing of the point still keeps a trace of weight,
    // so a point all of whose probes are occluded blends them rather than going black.
    w = max(w, 1e-4);
    vec3 t = mix(1.0 - f, f, vec3(o));
    w *= t.x * t.y * t.z;
    sum += w * volumeProbeIrradiance(probe, n);
    total += w;
  }
  if (total <= 0.0) return false;
  irradiance = sum / total;
  return true;
}
