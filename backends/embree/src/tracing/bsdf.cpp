#include "tracing/bsdf.hpp"

#include "tsr/embree/sampling.hpp"

#include <algorithm>
#include <cmath>

namespace tsr::embree {

namespace {

float ggxD(const glm::vec3& h, float a) {
  if (h.z <= 0.0f) return 0.0f;
  float a2 = a * a;
  float t = h.z * h.z * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * t * t);
}

float ggxLambda(const glm::vec3& w, float a) {
  float c2 = w.z * w.z;
  if (c2 <= 0.0f) return 0.0f;
  float t2 = std::max(0.0f, 1.0f - c2) / c2;
  return 0.5f * (-1.0f + std::sqrt(1.0f + a * a * t2));
}

float ggxG1(const glm::vec3& w, float a) { return 1.0f / (1.0f + ggxLambda(w, a)); }
float ggxG2(const glm::vec3& wo, const glm::vec3& wi, float a) {
  return 1.0f / (1.0f + ggxLambda(wo, a) + ggxLambda(wi, a));
}

// Density of visible normals (Heitz 2018), wo.z > 0.
float ggxVisiblePdf(const glm::vec3& wo, const glm::vec3& h, float a) {
  float dot = glm::dot(wo, h);
  if (dot <= 0.0f) return 0.0f;
  return ggxG1(wo, a) * dot * ggxD(h, a) / wo.z;
}

glm::vec3 sampleGgxVisible(const glm::vec3& wo, float a, const glm::vec2& u) {
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

glm::vec3 reflect(const glm::vec3& wo, const glm::vec3& h) { return 2.0f * glm::dot(wo, h) * h - wo; }

// Refracts wo (on the side h points to) through a surface with relative index eta.
bool refract(const glm::vec3& wo, const glm::vec3& h, float eta, glm::vec3& wi) {
  float cosI = glm::dot(wo, h);
  float sin2T = std::max(0.0f, 1.0f - cosI * cosI) / (eta * eta);
  if (sin2T >= 1.0f) return false;
  float cosT = std::sqrt(1.0f - sin2T);
  wi = -wo / eta + (cosI / eta - cosT) * h;
  return true;
}

glm::vec3 schlick(const glm::vec3& f0, float cosTheta) {
  float m = std::clamp(1.0f - cosTheta, 0.0f, 1.0f);
  float m5 = (m * m) * (m * m) * m;
  return f0 + (glm::vec3(1.0f) - f0) * m5;
}

}  // namespace

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
      float d = ggxD(h, alpha);
      return schlick(colour, glm::dot(wo, h)) * (d * ggxG2(wo, wi, alpha) / (4.0f * wo.z));
    }
    case MaterialType::Dielectric: {
      if (wi.z > 0.0f) {
        glm::vec3 h = glm::normalize(wo + wi);
        float f = fresnelDielectric(glm::dot(wo, h), eta);
        return glm::vec3(f * ggxD(h, alpha) * ggxG2(wo, wi, alpha) / (4.0f * wo.z));
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
          (1.0f - f) * ggxD(h, alpha) * ggxG2(wo, wi, alpha) * eta * eta * std::abs(ih) * oh / (wo.z * denom * denom);
      return colour * value;
    }
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
      return ggxVisiblePdf(wo, h, alpha) / (4.0f * glm::dot(wo, h));
    }
    case MaterialType::Dielectric: {
      if (wi.z > 0.0f) {
        glm::vec3 h = glm::normalize(wo + wi);
        float oh = glm::dot(wo, h);
        return fresnelDielectric(oh, eta) * ggxVisiblePdf(wo, h, alpha) / (4.0f * oh);
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
      return (1.0f - fresnelDielectric(oh, eta)) * ggxVisiblePdf(wo, h, alpha) * eta * eta * std::abs(ih) /
             (denom * denom);
    }
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
      glm::vec3 h = sampleGgxVisible(wo, alpha, u);
      out.wi = reflect(wo, h);
      if (out.wi.z <= 0.0f) return false;
      float oh = glm::dot(wo, h);
      out.pdf = ggxVisiblePdf(wo, h, alpha) / (4.0f * oh);
      // f cos / pdf simplifies to F * G2 / G1(wo).
      out.weight = schlick(colour, oh) * (ggxG2(wo, out.wi, alpha) / ggxG1(wo, alpha));
      out.delta = false;
      return out.pdf > 0.0f;
    }
    case MaterialType::Dielectric: {
      glm::vec3 h = sampleGgxVisible(wo, alpha, u);
      float oh = glm::dot(wo, h);
      if (oh <= 0.0f) return false;
      float f = fresnelDielectric(oh, eta);
      if (uLobe < f) {
        out.wi = reflect(wo, h);
        if (out.wi.z <= 0.0f) return false;
        out.pdf = f * ggxVisiblePdf(wo, h, alpha) / (4.0f * oh);
        out.weight = glm::vec3(ggxG2(wo, out.wi, alpha) / ggxG1(wo, alpha));
      } else {
        if (!refract(wo, h, eta, out.wi) || out.wi.z >= 0.0f) return false;
        float ih = glm::dot(out.wi, h);
        float denom = oh + eta * ih;
        out.pdf = (1.0f - f) * ggxVisiblePdf(wo, h, alpha) * eta * eta * std::abs(ih) / (denom * denom);
        out.weight = colour * (ggxG2(wo, out.wi, alpha) / ggxG1(wo, alpha));
      }
      out.delta = false;
      return out.pdf > 0.0f;
    }
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

}  // namespace tsr::embree
