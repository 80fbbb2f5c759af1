// Microfacet and Fresnel terms shared by mesh.frag and volume.frag; the
// Embree back-end's definitions.

const float PI = 3.14159265358979;

float ggxD(float nh, float a) {
  if (nh <= 0.0) return 0.0;
  float a2 = a * a;
  float t = nh * nh * (a2 - 1.0) + 1.0;
  return a2 / (PI * t * t);
}

float ggxLambda(float c, float a) {
  float c2 = c * c;
  if (c2 <= 0.0) return 0.0;
  float t2 = max(0.0, 1.0 - c2) / c2;
  return 0.5 * (-1.0 + sqrt(1.0 + a * a * t2));
}

float ggxG2(float co, float ci, float a) { return 1.0 / (1.0 + ggxLambda(co, a) + ggxLambda(ci, a)); }

vec3 schlick(vec3 f0, float c) {
  float m = clamp(1.0 - c, 0.0, 1.0);
  float m5 = (m * m) * (m * m) * m;
  return f0 + (vec3(1.0) - f0) * m5;
}

float fresnelDielectric(float cosI, float eta) {
  cosI = clamp(cosI, 0.0, 1.0);
  float sin2T = (1.0 - cosI * cosI) / (eta * eta);
  if (sin2T >= 1.0) return 1.0;
  float cosT = sqrt(1.0 - sin2T);
  float rs = (cosI - eta * cosT) / (cosI + eta * cosT);
  float rp = (eta * cosI - cosT) / (eta * cosI + cosT);
  return 0.5 * (rs * rs + rp * rp);
}
