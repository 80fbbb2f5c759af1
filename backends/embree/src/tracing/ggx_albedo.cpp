#include "tracing/ggx_albedo.hpp"

#include "tracing/ggx.hpp"

#include <array>

namespace tsr::embree {

namespace {

constexpr int kCells = 32;   // table resolution in cos theta and in alpha
constexpr int kStrata = 24;  // visible normals per cell, kStrata^2 of them
constexpr float kMinAlpha = 1e-3f;

struct AlbedoTable {
  std::array<GgxAlbedo, kCells * kCells> e;
  std::array<float, kCells> average;

  static float coordinate(int i) { return float(i) / float(kCells - 1); }

  AlbedoTable() {
    for (int ia = 0; ia < kCells; ++ia) {
      const float a = std::max(kMinAlpha, coordinate(ia));
      float avg = 0.0f;
      for (int ic = 0; ic < kCells; ++ic) {
        const float c = std::max(1e-3f, coordinate(ic));
        const glm::vec3 wo(std::sqrt(1.0f - c * c), 0.0f, c);
        // Sampling visible normals, f cos / pdf is G2 / G1(wo) per sample;
        // stratified so the table is the same on every run.
        double scale = 0.0, bias = 0.0;
        for (int i = 0; i < kStrata; ++i)
          for (int j = 0; j < kStrata; ++j) {
            const glm::vec2 u((float(i) + 0.5f) / kStrata, (float(j) + 0.5f) / kStrata);
            const glm::vec3 h = ggx::sampleVisible(wo, a, u);
            const glm::vec3 wi = ggx::reflect(wo, h);
            if (wi.z <= 0.0f) continue;
            const float w = ggx::G2(wo, wi, a) / ggx::G1(wo, a);
            const float m = std::clamp(1.0f - glm::dot(wo, h), 0.0f, 1.0f);
            const float m5 = (m * m) * (m * m) * m;
            scale += w * (1.0f - m5);
            bias += w * m5;
          }
        GgxAlbedo& cell = e[std::size_t(ia * kCells + ic)];
        cell.scale = float(scale / (kStrata * kStrata));
        cell.bias = float(bias / (kStrata * kStrata));
        // Trapezoid rule over cos theta for 2 * int E(c) c dc.
        const float weight = (ic == 0 || ic == kCells - 1) ? 0.5f : 1.0f;
        avg += weight * cell.white() * coordinate(ic);
      }
      average[std::size_t(ia)] = 2.0f * avg / float(kCells - 1);
    }
  }
};

const AlbedoTable& table() {
  static const AlbedoTable t;
  return t;
}

// Index and fraction of x in [0, 1] over the table's cells.
void locate(float x, int& i, float& f) {
  const float p = std::clamp(x, 0.0f, 1.0f) * float(kCells - 1);
  i = std::min(int(p), kCells - 2);
  f = p - float(i);
}

}  // namespace

GgxAlbedo ggxAlbedo(float cosTheta, float alpha) {
  const AlbedoTable& t = table();
  int ic, ia;
  float fc, fa;
  locate(cosTheta, ic, fc);
  locate(alpha, ia, fa);
  auto at = [&](int a, int c) { return t.e[std::size_t(a * kCells + c)]; };
  auto lerp = [](const GgxAlbedo& x, const GgxAlbedo& y, float f) {
    return GgxAlbedo{x.scale + (y.scale - x.scale) * f, x.bias + (y.bias - x.bias) * f};
  };
  return lerp(lerp(at(ia, ic), at(ia, ic + 1), fc), lerp(at(ia + 1, ic), at(ia + 1, ic + 1), fc), fa);
}

float ggxAverageAlbedo(float alpha) {
  const AlbedoTable& t = table();
  int ia;
  float fa;
  locate(alpha, ia, fa);
  return t.average[std::size_t(ia)] + (t.average[std::size_t(ia + 1)] - t.average[std::size_t(ia)]) * fa;
}

}  // namespace tsr::embree
