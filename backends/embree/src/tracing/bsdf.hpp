#pragma once

#include "tsr/embree/material.hpp"
#include "tsr/embree/sampling.hpp"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <bit>
#include <cmath>
#include <cstdint>

namespace tsr::embree {

struct BsdfSample {
  glm::vec3 wi{0.0f};
  glm::vec3 weight{0.0f};  // f * |cos| / pdf
  float pdf = 0.0f;        // solid angle; meaningless for delta lobes
  bool delta = false;
};

// A delta lobe taken whole, as a Whitted-style tracer follows it: its
// direction and the share of the light along it that leaves towards wo (f / pdf
// times the probability of picking the lobe).
struct SpecularLobe {
  glm::vec3 wi{0.0f};
  glm::vec3 weight{0.0f};
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

  // MetallicRoughness: what its lobes share at one outgoing direction
  // (selection probabilities, the diffuse base's weight, the layer's
  // albedo), computed here once for a scattering point instead of again in
  // every sample, eval and pdf call at that wo; the same values, so the
  // same bits. Call it after the parameters are set; other types ignore it.
  void prepare(const glm::vec3& wo);

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
  // The delta lobes at wo, at most two (reflection, refraction), each with
  // its whole weight: perfect mirrors and glass, smooth MetallicRoughness,
  // an Interface's straight passage. Rough lobes are not among them.
  int specularLobes(const glm::vec3& wo, SpecularLobe out[2]) const;

  // eval, and pdf into *pdf when asked: one call where MIS needs both.
  glm::vec3 evalPdf(const glm::vec3& wo, const glm::vec3& wi, float* pdf) const {
    if (type == MaterialType::Diffuse) {
      if (pdf) *pdf = wi.z > 0.0f ? wi.z * kInvPi : 0.0f;
      return wi.z > 0.0f ? colour * (kInvPi * wi.z) : glm::vec3(0.0f);
    }
    if (type == MaterialType::MetallicRoughness) {
      float p;
      const glm::vec3 f = evalPdfMetallicRoughness(wo, wi, p);
      if (pdf) *pdf = p;
      return f;
    }
    if (pdf) *pdf = pdfOther(wo, wi);
    return evalOther(wo, wi);
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
  // The lobes of MetallicRoughness at cos(theta_o), see metallic_roughness.cpp.
  struct Lobes {
    float etaOpaque;                    // the opaque dielectric's index ratio, always seen from outside
    float f0;                           // its Schlick F0, specular-weighted
    float diffuse;                      // weight of Lambert(colour): (1 - m)(1 - t)(1 - E_F(wo))
    glm::vec3 multiple;                 // metal's multiple-scattering colour, m F_ms / (pi (1 - E_avg)), 0 when smooth
    float eo;                           // E(wo) of GGX with F = 1
    float eavg;                         // its hemispherical average
    float pReflect, pRefract, pCosine;  // normalised selection probabilities
    float lambdaO, g1o;                 // Smith's lambda and G1 of wo (rough only), as ggx.hpp computes them
  };
  Lobes lobes(float cosO) const;
  // The prepared lobes when cosO is the prepared direction's (bit for bit), else computed.
  Lobes lobesAt(float cosO) const {
    return prepared_ && std::bit_cast<std::uint32_t>(cosO) == preparedCos_ ? preparedLobes_ : lobes(cosO);
  }
  bool prepared_ = false;
  std::uint32_t preparedCos_ = 0;
  Lobes preparedLobes_{};
  glm::vec3 evalMetallicRoughness(const glm::vec3& wo, const glm::vec3& wi) const;
  float pdfMetallicRoughness(const glm::vec3& wo, const glm::vec3& wi) const;
  int specularLobesMetallicRoughness(const glm::vec3& wo, SpecularLobe out[2]) const;
  glm::vec3 evalPdfMetallicRoughness(const glm::vec3& wo, const glm::vec3& wi, float& pdf) const;
  bool sampleMetallicRoughness(const glm::vec3& wo, const glm::vec2& u, float uLobe, BsdfSample& out) const;
};

float fresnelDielectric(float cosI, float eta);

}  // namespace tsr::embree
