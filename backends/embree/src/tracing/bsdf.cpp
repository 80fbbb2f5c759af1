#include "tracing/bsdf.hpp"

#include "tracing/ggx.hpp"
#include "tsr/embree/sampling.hpp"

#include <algorithm>
#include <cmath>

namespace tsr::embree {

using namespace ggx;

float fresnelDielectric(float cosI, float eta) {
  cosI = std::clamp(cosI, 0.0f, 1.0f);
  float sin2T = (1.0f - cosI * cosI) / (eta * eta);
  if (sin2T >= 1.0f) return 1.0f;
  float cosT = std::sqrt(1.0f - sin2T);
  float rs = (cosI - eta * cosT) / (cosI + eta * cosT);
  float rp = (eta * cosI - cosT) / (eta * cosI + cosT);
  return 0.5f * (rs * rs + rp * rp);
}

glm::vec3 Bsdf::evalOther(const glm::vec3& wo, const glm::vec3& wi) const {
  switch (type) {
    case MaterialType::Diffuse:  // inline in bsdf.hpp
      return eval(wo, wi);
    case MaterialType::Conductor: {
      if (wi.z <= 0.0f) return glm::vec3(0.0f);
      glm::vec3 h = glm::normalize(wo + wi);
      float d = D(h, alpha);
      return schlick(colour, glm::dot(wo, h)) * (d * G2(wo, wi, alpha) / (4.0f * wo.z));
    }
    case MaterialType::Dielectric: {
      if (wi.z > 0.0f) {
        glm::vec3 h = glm::normalize(wo + wi);
        float f = fresnelDielectric(glm::dot(wo, h), eta);
        return glm::vec3(f * D(h, alpha) * G2(wo, wi, alpha) / (4.0f * wo.z));
      }
      if (wi.z == 0.0f) return glm::vec3(0.0f);
      glm::vec3 h = wo + eta * wi;
      if (glm::dot(h, h) <= 0.0f) return glm::vec3(0.0f);
      h = glm::normalize(h);
      if (h.z < 0.0f) h = -h;
      float oh = glm::dot(wo, h);
      float ih = glm::dot(wi, h);
      if (oh <= 0.0f || ih >= 0.0f) return glm::vec3(0.0f);
      float f = fresnelDielectric(oh, eta);
      float denom = oh + eta * ih;
      float value =
          (1.0f - f) * D(h, alpha) * G2(wo, wi, alpha) * eta * eta * std::abs(ih) * oh / (wo.z * denom * denom);
      return colour * value;
    }
    case MaterialType::MetallicRoughness:
      return evalMetallicRoughness(wo, wi);
    case MaterialType::Mirror:
    case MaterialType::Glass:
    case MaterialType::Interface:
      return glm::vec3(0.0f);
  }
  return glm::vec3(0.0f);
}

float Bsdf::pdfOther(const glm::vec3& wo, const glm::vec3& wi) const {
  switch (type) {
    case MaterialType::Diffuse:  // inline in bsdf.hpp
      return pdf(wo, wi);
    case MaterialType::Conductor: {
      if (wi.z <= 0.0f) return 0.0f;
      glm::vec3 h = glm::normalize(wo + wi);
      return visiblePdf(wo, h, alpha) / (4.0f * glm::dot(wo, h));
    }
    case MaterialType::Dielectric: {
      if (wi.z > 0.0f) {
        glm::vec3 h = glm::normalize(wo + wi);
        float oh = glm::dot(wo, h);
        return fresnelDielectric(oh, eta) * visiblePdf(wo, h, alpha) / (4.0f * oh);
      }
      if (wi.z == 0.0f) return 0.0f;
      glm::vec3 h = wo + eta * wi;
      if (glm::dot(h, h) <= 0.0f) return 0.0f;
      h = glm::normalize(h);
      if (h.z < 0.0f) h = -h;
      float oh = glm::dot(wo, h);
      float ih = glm::dot(wi, h);
      if (oh <= 0.0f || ih >= 0.0f) return 0.0f;
      float denom = oh + eta * ih;
      return (1.0f - fresnelDielectric(oh, eta)) * visiblePdf(wo, h, alpha) * eta * eta * std::abs(ih) /
             (denom * denom);
    }
    case MaterialType::MetallicRoughness:
      return pdfMetallicRoughness(wo, wi);
    case MaterialType::Mirror:
    case MaterialType::Glass:
    case MaterialType::Interface:
      return 0.0f;
  }
  return 0.0f;
}

bool Bsdf::sampleOther(const glm::vec3& wo, const glm::vec2& u, float uLobe, BsdfSample& out) const {
  switch (type) {
    case MaterialType::Diffuse:  // inline in bsdf.hpp
      return sample(wo, u, uLobe, out);
    case MaterialType::Conductor: {
      glm::vec3 h = sampleVisible(wo, alpha, u);
      out.wi = reflect(wo, h);
      if (out.wi.z <= 0.0f) return false;
      float oh = glm::dot(wo, h);
      out.pdf = visiblePdf(wo, h, alpha) / (4.0f * oh);
      // f cos / pdf simplifies to F * G2 / G1(wo).
      out.weight = schlick(colour, oh) * (G2(wo, out.wi, alpha) / G1(wo, alpha));
      out.delta = false;
      return out.pdf > 0.0f;
    }
    case MaterialType::Dielectric: {
      glm::vec3 h = sampleVisible(wo, alpha, u);
      float oh = glm::dot(wo, h);
      if (oh <= 0.0f) return false;
      float f = fresnelDielectric(oh, eta);
      if (uLobe < f) {
        out.wi = reflect(wo, h);
        if (out.wi.z <= 0.0f) return false;
        out.pdf = f * visiblePdf(wo, h, alpha) / (4.0f * oh);
        out.weight = glm::vec3(G2(wo, out.wi, alpha) / G1(wo, alpha));
      } else {
        if (!refract(wo, h, eta, out.wi) || out.wi.z >= 0.0f) return false;
        float ih = glm::dot(out.wi, h);
        float denom = oh + eta * ih;
        out.pdf = (1.0f - f) * visiblePdf(wo, h, alpha) * eta * eta * std::abs(ih) / (denom * denom);
        out.weight = colour * (G2(wo, out.wi, alpha) / G1(wo, alpha));
      }
      out.delta = false;
      return out.pdf > 0.0f;
    }
    case MaterialType::MetallicRoughness:
      return sampleMetallicRoughness(wo, u, uLobe, out);
    case MaterialType::Mirror: {
      out.wi = {-wo.x, -wo.y, wo.z};
      out.weight = colour;
      out.pdf = 1.0f;
      out.delta = true;
      return true;
    }
    case MaterialType::Interface: {  // straight on: no surface is there
      out.wi = -wo;
      out.weight = glm::vec3(1.0f);
      out.pdf = 1.0f;
      out.delta = true;
      return true;
    }
    case MaterialType::Glass: {
      float f = fresnelDielectric(wo.z, eta);
      out.delta = true;
      out.pdf = 1.0f;
      if (uLobe < f) {
        out.wi = {-wo.x, -wo.y, wo.z};
        out.weight = glm::vec3(1.0f);
        return true;
      }
      if (!refract(wo, glm::vec3(0.0f, 0.0f, 1.0f), eta, out.wi)) return false;
      out.weight = colour;
      return true;
    }
  }
  return false;
}

int Bsdf::specularLobes(const glm::vec3& wo, SpecularLobe out[2]) const {
  switch (type) {
    case MaterialType::Mirror:
      out[0] = {{-wo.x, -wo.y, wo.z}, colour};
      return 1;
    case MaterialType::Interface:
      out[0] = {-wo, glm::vec3(1.0f)};
      return 1;
    case MaterialType::Glass: {
      const float f = fresnelDielectric(wo.z, eta);
      out[0] = {{-wo.x, -wo.y, wo.z}, glm::vec3(f)};
      glm::vec3 wi;
      if (f >= 1.0f || !refract(wo, glm::vec3(0.0f, 0.0f, 1.0f), eta, wi)) return 1;  // total internal reflection
      out[1] = {wi, (1.0f - f) * colour};
      return 2;
    }
    case MaterialType::MetallicRoughness:
      return specularLobesMetallicRoughness(wo, out);
    case MaterialType::Diffuse:
    case MaterialType::Conductor:
    case MaterialType::Dielectric:
      return 0;
  }
  return 0;
}

}  // namespace tsr::embree
