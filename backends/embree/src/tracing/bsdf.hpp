#pragma once

#include "tsr/embree/material.hpp"
#include "tsr/embree/sampling.hpp"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cmath>

namespace tsr::embree {

struct BsdfSample {
  glm::vec3 wi{0.0f};
  glm::vec3 weight{0.0f};  // f * |cos| / pdf
  float pdf = 0.0f;        // solid angle; meaningless for delta lobes
  bool delta = false;
};

// A material evaluated at one point, in the local shading frame (z = shading
// normal, flipped to the side of wo, so wo.z > 0). eta is the index ratio
// across the surface as seen from wo (inside/outside when entering).
// Refraction does not scale radiance by eta^2; for closed objects seen from
// outside the factors cancel.
struct Bsdf {
  MaterialType type = MaterialType::Diffuse;
  glm::vec3 colour{0.0f};
  float alpha = 0.25f;
  float eta = 1.5f;
  // MetallicRoughness only (see metallic_roughness.cpp).
  float metallic = 0.0f;
  float specular = 1.0f;
  float transmission = 0.0f;

  // Every lobe is a delta lobe: no light sampling, no MIS.
  bool isDelta() const {
    if (type == MaterialType::MetallicRoughness) return smooth() && (1.0f - metallic) * (1.0f - transmission) <= 0.0f;
    return type == MaterialType::Mirror || type == MaterialType::Glass || type == MaterialType::Interface;
  }
  // MetallicRoughness: alpha is 0 below kSmoothRoughness, where the
  // specular lobes are delta lobes.
  bool smooth() const { return alpha <= 0.0f; }
  // The class the filters and photons treat it as.
  MaterialType closest() const { return closestClass(type, std::sqrt(alpha), metallic, transmission); }
  // Diffuse, the common case, is inlined into the integrator; the rest
  // goes through the out-of-line *Other functions.
  glm::vec3 eval(const glm::vec3& wo, const glm::vec3& wi) const {  // f * |cos(wi)|
    if (type != MaterialType::Diffuse) return evalOther(wo, wi);
    return wi.z > 0.0f ? colour * (kInvPi * wi.z) : glm::vec3(0.0f);
  }
  float pdf(const glm::vec3& wo, const glm::vec3& wi) const {
    if (type != MaterialType::Diffuse) return pdfOther(wo, wi);
    return wi.z > 0.0f ? wi.z * kInvPi : 0.0f;
  }
  bool sample(const glm::vec3& wo, const glm::vec2& u, float uLobe, BsdfSample& out) const {
    if (type != MaterialType::Diffuse) return sampleOther(wo, u, uLobe, out);
    out.wi = sampleCosineHemisphere(u);
    out.pdf = out.wi.z * kInvPi;
    out.weight = colour;
    out.delta = false;
    return out.pdf > 0.0f;
  }

 private:
  glm::vec3 evalOther(const glm::vec3& wo, const glm::vec3& wi) const;
  float pdfOther(const glm::vec3& wo, const glm::vec3& wi) const;
  bool sampleOther(const glm::vec3& wo, const glm::vec2& u, float uLobe, BsdfSample& out) const;
  struct Lobes;
  Lobes lobes(float cosO) const;
  glm::vec3 evalMetallicRoughness(const glm::vec3& wo, const glm::vec3& wi) const;
  float pdfMetallicRoughness(const glm::vec3& wo, const glm::vec3& wi) const;
  bool sampleMetallicRoughness(const glm::vec3& wo, const glm::vec2& u, float uLobe, BsdfSample& out) const;
};

float fresnelDielectric(float cosI, float eta);

}  // namespace tsr::embree
