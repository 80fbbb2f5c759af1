// Reflection-probe lookups (src/reflection_probe.cpp draws the faces). A
// direction from a point inside the scene's bounds is first followed to
// the bounds' box and looked up from the probe's centre towards that hit
// (box-projected, "parallax-corrected" cube mapping), which is exact for a
// room whose walls are its bounds. Needs common.glsl.

bool hasProbe() { return frame.probeCentre.w > 0.0; }

vec3 probeRadiance(vec3 p, vec3 dir) {
  vec3 lo = frame.sceneMin.xyz, hi = frame.sceneMax.xyz;
  vec3 d = dir;
  if (all(greaterThanEqual(p, lo)) && all(lessThanEqual(p, hi))) {
    vec3 safe = vec3(abs(dir.x) > 1e-6 ? dir.x : 1e-6, abs(dir.y) > 1e-6 ? dir.y : 1e-6,
                     abs(dir.z) > 1e-6 ? dir.z : 1e-6);
    vec3 far = max((hi - p) / safe, (lo - p) / safe);
    float t = min(far.x, min(far.y, far.z));
    d = p + dir * max(t, 0.0) - frame.probeCentre.xyz;
  }
  // The face of the major axis, with the forward and up it was drawn with.
  vec3 a = abs(d);
  float layer;
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
  vec2 uv = vec2(0.5 + 0.5 * dot(d, right) / w, 0.5 - 0.5 * dot(d, up) / w);
  return texture(reflectionProbe, vec3(clamp(uv, vec2(0.5 / 128.0), vec2(1.0 - 0.5 / 128.0)), layer)).rgb;
}
