// What light i delivers at p: the direction towards it (wi) and the
// irradiance on a surface facing it (li). False when it delivers nothing.
// Needs common.glsl and brdf.glsl (PI). Lights are read field by field:
// copying the whole struct (with its matrix) per fragment is costly on CPU
// rasterizers.

const uint POINT = 0u, SPOT = 1u, DIRECTIONAL = 2u, EMITTER = 3u;

bool lightAt(uint i, vec3 p, out vec3 wi, out vec3 li) {
  vec4 position = lights[i].position;
  vec4 direction = lights[i].direction;
  uint lt = uint(position.w);
  if (lt == DIRECTIONAL) {
    wi = -direction.xyz;
    li = lights[i].intensity.rgb;
    return true;
  }
  vec3 d = position.xyz - p;
  float d2 = dot(d, d);
  wi = vec3(0.0);
  li = vec3(0.0);
  if (!(d2 > 0.0)) return false;
  wi = d / sqrt(d2);
  li = lights[i].intensity.rgb / d2;
  if (lt == EMITTER) {
    // A patch of area A: radiance x projected area, over d^2 + A / pi
    // (a disc's on-axis irradiance), so it stays finite up close.
    float area = lights[i].intensity.w;
    float directional = lights[i].cone.x;
    float projected = directional * max(dot(direction.xyz, -wi), 0.0) + 0.25 * (area - directional);
    if (projected <= 0.0) return false;
    li = lights[i].intensity.rgb * (projected / (d2 + area / PI));
  } else if (lt == SPOT) {
    vec4 cone = lights[i].cone;
    float c = dot(direction.xyz, -wi);
    float falloff = c >= cone.x ? 1.0 : (c <= cone.y ? 0.0 : smoothstep(cone.y, cone.x, c));
    if (falloff <= 0.0) return false;
    li *= falloff;
  }
  return true;
}

// Whether p is lit by light i, by one tap of its shadow map (1 outside it).
float shadowTap(uint i, vec3 p) {
  vec4 c = lights[i].shadowMatrix * vec4(p, 1.0);
  if (c.w <= 0.0) return 1.0;
  vec3 s = c.xyz / c.w;
  vec2 st = s.xy * 0.5 + 0.5;
  if (any(lessThan(st, vec2(0.0))) || any(greaterThan(st, vec2(1.0))) || s.z < 0.0 || s.z > 1.0) return 1.0;
  return texture(shadowMaps, vec4(st, lights[i].direction.w, s.z));
}
