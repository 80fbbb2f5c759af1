#pragma once

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tsr::embree {

inline constexpr float kPi = std::numbers::pi_v<float>;
inline constexpr float kInvPi = 1.0f / kPi;

inline float luminance(const glm::vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }
inline float maxComponent(const glm::vec3& c) { return std::max(c.x, std::max(c.y, c.z)); }

// Orthonormal basis around a unit normal (Duff et al. 2017, branchless).
struct Frame {
  glm::vec3 t, b, n;
  explicit Frame(const glm::vec3& normal) : n(normal) {
    float sign = std::copysign(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float c = n.x * n.y * a;
    t = {1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x};
    b = {c, sign + n.y * n.y * a, -n.y};
  }
  glm::vec3 toLocal(const glm::vec3& v) const { return {glm::dot(v, t), glm::dot(v, b), glm::dot(v, n)}; }
  glm::vec3 toWorld(const glm::vec3& v) const { return v.x * t + v.y * b + v.z * n; }
};

// (cos, sin) of 2*pi*u for u in [0, 1], within 4e-7 of the library's
// values: every bounce samples an azimuth, and sincosf's general argument
// reduction cost more than the rest of a diffuse bounce's sampling.
inline glm::vec2 cosSin2Pi(float u) {
  const int q = int(4.0f * u + 0.5f);  // nearest quadrant: 2*pi*u = q*pi/2 + x
  const float x = (4.0f * u - float(q)) * (0.5f * kPi);
  const float x2 = x * x;  // |x| <= pi/4: short Taylor series suffice
  const float s = x * (1.0f + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040 + x2 * (1.0f / 362880)))));
  const float c = 1.0f + x2 * (-0.5f + x2 * (1.0f / 24 + x2 * (-1.0f / 720 + x2 * (1.0f / 40320))));
  // Rotate by q quarter turns without branching (the quadrant is random, so
  // a branch would be mispredicted one time in four or more).
  const float cs[2] = {c, s};
  const int odd = q & 1;
  constexpr float kCosSign[4] = {1.0f, -1.0f, -1.0f, 1.0f};
  constexpr float kSinSign[4] = {1.0f, 1.0f, -1.0f, -1.0f};
  return {kCosSign[q & 3] * cs[odd], kSinSign[q & 3] * cs[odd ^ 1]};
}

inline glm::vec3 sampleCosineHemisphere(const glm::vec2& u) {
  float r = std::sqrt(u.x);
  glm::vec2 cs = cosSin2Pi(u.y);
  return {r * cs.x, r * cs.y, std::sqrt(std::max(0.0f, 1.0f - u.x))};
}

inline glm::vec3 sampleUniformSphere(const glm::vec2& u) {
  float z = 1.0f - 2.0f * u.x;
  float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  glm::vec2 cs = cosSin2Pi(u.y);
  return {r * cs.x, r * cs.y, z};
}
inline constexpr float kUniformSpherePdf = 1.0f / (4.0f * std::numbers::pi_v<float>);

// Barycentrics (b1, b2) of a uniformly distributed point on a triangle.
inline glm::vec2 sampleTriangle(const glm::vec2& u) {
  float s = std::sqrt(u.x);
  return {1.0f - s, u.y * s};
}

inline float powerHeuristic(float pdfA, float pdfB) {
  float a = pdfA * pdfA;
  float b = pdfB * pdfB;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
}

}  // namespace tsr::embree
