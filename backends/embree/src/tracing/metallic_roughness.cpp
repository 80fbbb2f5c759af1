// The glTF 2.0 metallic-roughness BSDF (specification appendix B), with
// KHR_materials_specular's weight and KHR_materials_transmission:
//
//   metal      = GGX reflection, Schlick Fresnel with F0 = base colour,
//                plus Kulla-Conty multiple scattering so rough metal keeps
//                its energy
//   dielectric = GGX reflection with the Fresnel of the ior (times the
//                specular weight) over
//                  (1 - transmission) Lambert(base colour), scaled by what
//                  the reflection leaves (1 - its directional albedo), and
//                  transmission x rough GGX refraction tinted by base colour
//   f          = mix(dielectric, metal, metallic)
//
// Four lobes are sampled: reflection (visible normals), refraction (visible
// normals), and one cosine lobe for the diffuse base and the metal's
// multiple scattering. A lobe is picked with a probability proportional to
// its estimated albedo seen from wo; eval and pdf are the sums over lobes,
// so every non-delta sample is weighted f cos / pdf with the same
// functions MIS uses. Below kSmoothRoughness reflection and refraction are
// delta lobes: sampled with delta = true and absent from eval and pdf.
#include "tracing/bsdf.hpp"
#include "tracing/ggx.hpp"
#include "tracing/ggx_albedo.hpp"

namespace tsr::embree {

using namespace ggx;

namespace {

float schlickScalar(float f0, float f90, float c) {
  float m = std::clamp(1.0f - c, 0.0f, 1.0f);
  float m5 = (m * m) * (m * m) * m;
  return f0 + (f90 - f0) * m5;
}

}  // namespace

void Bsdf::prepare(const glm::vec3& wo) {
  prepared_ = false;
  if (type != MaterialType::MetallicRoughness) return;
  preparedLobes_ = lobes(wo.z);
  preparedCos_ = std::bit_cast<std::uint32_t>(wo.z);
  prepared_ = true;
}

Bsdf::Lobes Bsdf::lobes(float cosO) const {
  Lobes l;
  const float m = metallic, t = transmission;
  l.etaOpaque = eta < 1.0f ? 1.0f / eta : eta;
  const float r = (l.etaOpaque - 1.0f) / (l.etaOpaque + 1.0f);
  l.f0 = specular * r * r;
  const GgxAlbedo e = smooth() ? GgxAlbedo{} : ggxAlbedo(cosO, alpha);
  l.eo = smooth() ? 1.0f : e.white();
  const float layer = smooth() ? schlickScalar(l.f0, specular, cosO) : l.f0 * e.scale + specular * e.bias;
  l.diffuse = (1.0f - m) * (1.0f - t) * std::max(0.0f, 1.0f - layer);
  l.lambdaO = smooth() ? 0.0f : lambda(glm::vec3(0.0f, 0.0f, cosO), alpha);
  l.g1o = 1.0f / (1.0f + l.lambdaO);
  l.multiple = glm::vec3(0.0f);
  l.eavg = 1.0f;
  if (m > 0.0f && !smooth()) {
    const float eavg = l.eavg = ggxAverageAlbedo(alpha);
    const glm::vec3 favg = colour + (glm::vec3(1.0f) - colour) / 21.0f;
    const glm::vec3 fms = favg * favg * eavg / (glm::vec3(1.0f) - favg * (1.0f - eavg));
    l.multiple = m * fms / (kPi * std::max(1e-4f, 1.0f - eavg));
  }
  // Without transmission the dielectric's Fresnel is multiplied by t = 0:
  // not computed, the same sums.
  const float fresnel = t != 0.0f ? fresnelDielectric(cosO, eta) : 0.0f;
  const glm::vec3 fr = (1.0f - m) * ((1.0f - t) * schlickScalar(l.f0, specular, cosO) + t * specular * fresnel) +
                       m * schlick(colour, cosO);
  const float wReflect = luminance(fr);
  const float wRefract = (1.0f - m) * t * (1.0f - specular * fresnel) * luminance(colour);
  const float wCosine = l.diffuse * luminance(colour) + luminance(l.multiple) * kPi * (1.0f - l.eo) * (1.0f - l.eavg);
  const float sum = wReflect + wRefract + wCosine;
  const float inv = sum > 0.0f ? 1.0f / sum : 0.0f;
  l.pReflect = wReflect * inv;
  l.pRefract = wRefract * inv;
  l.pCosine = wCosine * inv;
  return l;
}

namespace {

// Fresnel of the reflection lobe at a microfacet: the opaque and the
// transmissive dielectric and the metal, mixed by their weights.
glm::vec3 reflectance(const Bsdf& b, float f0, float c) {
  const float m = b.metallic, t = b.transmission;
  // The two common cases without the terms they multiply by zero: an
  // opaque dielectric and a metal. Each term is finite and non-negative,
  // so 1 x a + 0 x b is a to the bit and the sums below are unchanged.
  if (t == 0.0f && m == 0.0f) return glm::vec3(schlickScalar(f0, b.specular, c));
  if (t == 0.0f && m == 1.0f) return schlick(b.colour, c);
  const float fresnel = t != 0.0f ? fresnelDielectric(c, b.eta) : 0.0f;  // as in Bsdf::lobes
  return (1.0f - m) * ((1.0f - t) * schlickScalar(f0, b.specular, c) + t * b.specular * fresnel) +
         m * schlick(b.colour, c);
}

// Rough refraction's f |cos wi| through the microfacet h (without the
// transmission weight and tint), and its density given the lobe.
float refractionValue(const glm::vec3& wo, const glm::vec3& wi, const glm::vec3& h, float alpha, float eta,
                      float specular) {
  const float oh = glm::dot(wo, h), ih = glm::dot(wi, h);
  const float denom = oh + eta * ih;
  const float f = specular * fresnelDielectric(oh, eta);
  return (1.0f - f) * D(h, alpha) * G2(wo, wi, alpha) * eta * eta * std::abs(ih) * oh / (wo.z * denom * denom);
}

float refractionPdf(const glm::vec3& wo, const glm::vec3& wi, const glm::vec3& h, float alpha, float eta) {
  const float oh = glm::dot(wo, h), ih = glm::dot(wi, h);
  const float denom = oh + eta * ih;
  return visiblePdf(wo, h, alpha) * eta * eta * std::abs(ih) / (denom * denom);
}

}  // namespace

glm::vec3 Bsdf::evalMetallicRoughness(const glm::vec3& wo, const glm::vec3& wi) const {
  const Lobes l = lobesAt(wo.z);
  if (wi.z > 0.0f) {
    glm::vec3 f = l.diffuse * colour * (kInvPi * wi.z);
    if (smooth()) return f;
    if (metallic > 0.0f) f += l.multiple * ((1.0f - l.eo) * (1.0f - ggxAlbedo(wi.z, alpha).white()) * wi.z);
    const glm::vec3 h = glm::normalize(wo + wi);
    return f + reflectance(*this, l.f0, glm::dot(wo, h)) * (D(h, alpha) * G2(wo, wi, alpha) / (4.0f * wo.z));
  }
  glm::vec3 h;
  if (wi.z == 0.0f || smooth() || transmission <= 0.0f || metallic >= 1.0f || !refractionHalf(wo, wi, eta, h))
    return glm::vec3(0.0f);
  return (1.0f - metallic) * transmission * colour * refractionValue(wo, wi, h, alpha, eta, specular);
}

float Bsdf::pdfMetallicRoughness(const glm::vec3& wo, const glm::vec3& wi) const {
  const Lobes l = lobesAt(wo.z);
  if (wi.z > 0.0f) {
    float p = l.pCosine * wi.z * kInvPi;
    if (smooth() || l.pReflect <= 0.0f) return p;
    const glm::vec3 h = glm::normalize(wo + wi);
    const float oh = glm::dot(wo, h);
    return oh > 0.0f ? p + l.pReflect * visiblePdf(wo, h, alpha) / (4.0f * oh) : p;
  }
  glm::vec3 h;
  if (wi.z == 0.0f || smooth() || l.pRefract <= 0.0f || !refractionHalf(wo, wi, eta, h)) return 0.0f;
  return l.pRefract * refractionPdf(wo, wi, h, alpha, eta);
}

// evalMetallicRoughness and pdfMetallicRoughness in one: the lobes and the
// half vector once, each result by the same expressions as alone.
glm::vec3 Bsdf::evalPdfMetallicRoughness(const glm::vec3& wo, const glm::vec3& wi, float& pdf) const {
  const Lobes l = lobesAt(wo.z);
  if (wi.z > 0.0f) {
    glm::vec3 f = l.diffuse * colour * (kInvPi * wi.z);
    pdf = l.pCosine * wi.z * kInvPi;
    if (smooth()) return f;
    if (metallic > 0.0f) f += l.multiple * ((1.0f - l.eo) * (1.0f - ggxAlbedo(wi.z, alpha).white()) * wi.z);
    const glm::vec3 h = glm::normalize(wo + wi);
    const float oh = glm::dot(wo, h);
    // visiblePdf and G2 with wo's lambda from the lobes: the same operations.
    const float d = D(h, alpha);
    if (!(l.pReflect <= 0.0f) && oh > 0.0f) pdf = pdf + l.pReflect * (l.g1o * oh * d / wo.z) / (4.0f * oh);
    const float g2 = 1.0f / (1.0f + l.lambdaO + lambda(wi, alpha));
    return f + reflectance(*this, l.f0, oh) * (d * g2 / (4.0f * wo.z));
  }
  pdf = 0.0f;
  glm::vec3 h;
  if (wi.z == 0.0f || smooth() || !refractionHalf(wo, wi, eta, h)) return glm::vec3(0.0f);
  if (!(l.pRefract <= 0.0f)) pdf = l.pRefract * refractionPdf(wo, wi, h, alpha, eta);
  if (transmission <= 0.0f || metallic >= 1.0f) return glm::vec3(0.0f);
  return (1.0f - metallic) * transmission * colour * refractionValue(wo, wi, h, alpha, eta, specular);
}

bool Bsdf::sampleMetallicRoughness(const glm::vec3& wo, const glm::vec2& u, float uLobe, BsdfSample& out) const {
  const Lobes l = lobesAt(wo.z);
  out.delta = false;
  if (uLobe < l.pReflect) {
    if (smooth()) {
      out.wi = {-wo.x, -wo.y, wo.z};
      out.weight = reflectance(*this, l.f0, wo.z) / l.pReflect;
      out.pdf = l.pReflect;
      out.delta = true;
      return true;
    }
    out.wi = reflect(wo, sampleVisible(wo, alpha, u));
    if (out.wi.z <= 0.0f) return false;
  } else if (uLobe < l.pReflect + l.pRefract) {
    if (smooth()) {
      if (!refract(wo, glm::vec3(0.0f, 0.0f, 1.0f), eta, out.wi)) return false;
      const float f = specular * fresnelDielectric(wo.z, eta);
      out.weight = (1.0f - metallic) * transmission * (1.0f - f) * colour / l.pRefract;
      out.pdf = l.pRefract;
      out.delta = true;
      return true;
    }
    if (!refract(wo, sampleVisible(wo, alpha, u), eta, out.wi) || out.wi.z >= 0.0f) return false;
  } else {
    if (l.pCosine <= 0.0f) return false;
    out.wi = sampleCosineHemisphere(u);
  }
  const glm::vec3 f = evalPdfMetallicRoughness(wo, out.wi, out.pdf);
  if (!(out.pdf > 0.0f)) return false;
  out.weight = f / out.pdf;
  return std::isfinite(out.weight.x + out.weight.y + out.weight.z);
}

// The delta lobes of a smooth surface with the weights sampling gives them
// times the probabilities of picking them.
int Bsdf::specularLobesMetallicRoughness(const glm::vec3& wo, SpecularLobe out[2]) const {
  if (!smooth()) return 0;
  const Lobes l = lobesAt(wo.z);
  int n = 0;
  if (l.pReflect > 0.0f) out[n++] = {{-wo.x, -wo.y, wo.z}, reflectance(*this, l.f0, wo.z)};
  glm::vec3 wi;
  if (l.pRefract > 0.0f && refract(wo, glm::vec3(0.0f, 0.0f, 1.0f), eta, wi)) {
    const float f = specular * fresnelDielectric(wo.z, eta);
    out[n++] = {wi, (1.0f - metallic) * transmission * (1.0f - f) * colour};
  }
  return n;
}

}  // namespace tsr::embree
