#pragma once
// The GGX microfacet distribution in the local shading frame (z = normal):
// D, Smith's masking, visible-normal sampling (Heitz 2018), and the
// reflection and refraction geometry both microfacet BSDFs use. Private to
// the back-end.
#include "tsr/embree/sampling.hpp"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>

namespace tsr::embree::ggx {

inline float D(const glm::vec3& h, float a) {
  if (h.z <= 0.0f) return 0.0f;
  float a2 = a * a;
  float t = h.z * h.z * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * t * t);
}

inline float lambda(const glm::vec3& w, float a) {
  float c2 = w.z * w.z;
  if (c2 <= 0.0f) return 0.0f;
  float t2 = std::max(0.0f, 1.0f - c2) / c2;
  return 0.5f * (-1.0f + std::sqrt(1.0f + a * a * t2));
}

inline float G1(const glm::vec3& w, float a) { return 1.0f / (1.0f + lambda(w, a)); }
inline float G2(const glm::vec3& wo, const glm::vec3& wi, float a) {
  return 1.0f / (1.0f + lambda(wo, a) + lambda(wi, a));
}

// Density of visible normals, wo.z > 0.
inline float visiblePdf(const glm::vec3& wo, const glm::vec3& h, float a) {
  float dot = glm::dot(wo, h);
  if (dot <= 0.0f) return 0.0f;
  return G1(wo, a) * dot * D(h, a) / wo.z;
}

inline glm::vec3 sampleVisible(const glm::vec3& wo, float a, const glm::vec2& u) {
  glm::vec3 vh = glm::normalize(glm::vec3(a * wo.x, a * wo.y, wo.z));
  float lensq = vh.x * vh.x + vh.y * vh.y;
  glm::vec3 t1 = lensq > 0.0f ? glm::vec3(-vh.y, vh.x, 0.0f) / std::sqrt(lensq) : glm::vec3(1.0f, 0.0f, 0.0f);
  glm::vec3 t2 = glm::cross(vh, t1);
  float r = std::sqrt(u.x);
  float phi = 2.0f * kPi * u.y;
  float p1 = r * std::cos(phi);
  float p2 = r * std::sin(phi);
  float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * p2;
  glm::vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
  return glm::normalize(glm::vec3(a * nh.x, a * nh.y, std::max(1e-6f, nh.z)));
}

inline glm::vec3 reflect(const glm::vec3& wo, const glm::vec3& h) { return 2.0f * glm::dot(wo, h) * h - wo; }

// Refracts wo (on the side h points to) through a surface with relative index eta.
inline bool refract(const glm::vec3& wo, const glm::vec3& h, float eta, glm::vec3& wi) {
  float cosI = glm::dot(wo, h);
  float sin2T = std::max(0.0f, 1.0f - cosI * cosI) / (eta * eta);
  if (sin2T >= 1.0f) return false;
  float cosT = std::sqrt(1.0f - sin2T);
  wi = -wo / eta + (cosI / eta - cosT) * h;
  return true;
}

// The half vector of a refraction wo -> wi (wi.z < 0), on wo's side, and
// the Jacobian-weighted density / value factors shared by eval and pdf.
// False when the pair cannot be a refraction through index ratio eta.
inline bool refractionHalf(const glm::vec3& wo, const glm::vec3& wi, float eta, glm::vec3& h) {
  h = wo + eta * wi;
  if (glm::dot(h, h) <= 0.0f) return false;
  h = glm::normalize(h);
  if (h.z < 0.0f) h = -h;
  return glm::dot(wo, h) > 0.0f && glm::dot(wi, h) < 0.0f;
}

inline glm::vec3 schlick(const glm::vec3& f0, float cosTheta) {
  float m = std::clamp(1.0f - cosTheta, 0.0f, 1.0f);
  float m5 = (m * m) * (m * m) * m;
  return f0 + (glm::vec3(1.0f) - f0) * m5;
}

}  // namespace tsr::embree::ggx
