#include "reflections/brdf_table.hpp"
#include "reflections/radical_inverse.hpp"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tsr::vk {

namespace {
// As ggxLambda in shaders/brdf.glsl.
float lambda(float c, float a) {
  const float c2 = c * c;
  if (c2 <= 0.0f) return 0.0f;
  const float t2 = std::max(0.0f, 1.0f - c2) / c2;
  return 0.5f * (-1.0f + std::sqrt(1.0f + a * a * t2));
}
}  // namespace

std::vector<glm::vec2> splitSumTable(std::uint32_t size, std::uint32_t samples) {
  std::vector<glm::vec2> table(std::size_t(size) * size);
  for (std::uint32_t j = 0; j < size; ++j) {
    const float roughness = (float(j) + 0.5f) / float(size);
    const float a = std::max(1e-3f, roughness * roughness);
    for (std::uint32_t i = 0; i < size; ++i) {
      const float nv = (float(i) + 0.5f) / float(size);
      const glm::vec3 v(std::sqrt(1.0f - nv * nv), 0.0f, nv);
      double sumA = 0.0, sumB = 0.0;
      for (std::uint32_t k = 0; k < samples; ++k) {
        // A half vector from D(h) (n.h): cos^2 = (1 - u) / (1 + (a^2 - 1) u).
        const float u1 = (float(k) + 0.5f) / float(samples), u2 = radicalInverse(k);
        const float cosH = std::sqrt((1.0f - u1) / (1.0f + (a * a - 1.0f) * u1));
        const float sinH = std::sqrt(std::max(0.0f, 1.0f - cosH * cosH));
        const float phi = 2.0f * std::numbers::pi_v<float> * u2;
        const glm::vec3 h(sinH * std::cos(phi), sinH * std::sin(phi), cosH);
        const float vh = glm::dot(v, h);
        const glm::vec3 l = 2.0f * vh * h - v;
        if (l.z <= 0.0f || vh <= 0.0f) continue;
        // f cos / pdf with pdf = D n.h / (4 v.h): G2 v.h / (n.v n.h).
        const float g2 = 1.0f / (1.0f + lambda(nv, a) + lambda(l.z, a));
        const float w = g2 * vh / (nv * cosH);
        const float fc = std::pow(1.0f - vh, 5.0f);
        sumA += (1.0f - fc) * w;
        sumB += fc * w;
      }
      table[std::size_t(j) * size + i] = glm::vec2(float(sumA / samples), float(sumB / samples));
    }
  }
  return table;
}

std::vector<float> averageAlbedoByRow(const std::vector<glm::vec2>& table, std::uint32_t size) {
  std::vector<float> out(size, 0.0f);
  for (std::uint32_t j = 0; j < size; ++j) {
    double sum = 0.0;
    for (std::uint32_t i = 0; i < size; ++i) {
      const glm::vec2 ab = table[std::size_t(j) * size + i];
      sum += double(ab.x + ab.y) * ((double(i) + 0.5) / size);
    }
    out[j] = float(2.0 * sum / size);
  }
  return out;
}

}  // namespace tsr::vk
