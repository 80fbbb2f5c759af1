#include "tsr/vk/environment.hpp"
#include "reflections/ggx_prefilter.hpp"

#include "tsr/vk/error.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tsr::vk {

namespace {
bool finiteNonNegative(const glm::vec3& v) {
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(v[i]) || v[i] < 0.0f) return false;
  return true;
}
constexpr float kPi = std::numbers::pi_v<float>;

// Bilinear lookup of a lat-long map in the path tracer's convention,
// wrapping in u; at(x, y) wraps or clamps its arguments.
template <class At>
glm::vec3 bilinear(std::uint32_t width, std::uint32_t height, const glm::vec3& d, const At& at) {
  const float u = std::atan2(d.x, -d.z) / (2.0f * kPi) + 0.5f;
  const float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi;
  const float fx = u * float(width) - 0.5f, fy = v * float(height) - 0.5f;
  const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
  const float tx = fx - float(x0), ty = fy - float(y0);
  return (1.0f - ty) * ((1.0f - tx) * at(x0, y0) + tx * at(x0 + 1, y0)) +
         ty * ((1.0f - tx) * at(x0, y0 + 1) + tx * at(x0 + 1, y0 + 1));
}

struct LatLong {
  std::uint32_t width = 0, height = 0;
  std::vector<glm::vec3> texels;

  glm::vec3 at(int x, int y) const {
    x = ((x % int(width)) + int(width)) % int(width);
    y = std::clamp(y, 0, int(height) - 1);
    return texels[std::size_t(y) * width + std::size_t(x)];
  }
  glm::vec3 lookup(const glm::vec3& d) const {
    return bilinear(width, height, d, [this](int x, int y) { return at(x, y); });
  }
  // Box-averaged to at most w x h (sizes halve until they fit).
  LatLong reduced(std::uint32_t w, std::uint32_t h) const {
    LatLong r = *this;
    while (r.width > w || r.height > h) {
      LatLong n;
      n.width = std::max(1u, r.width / 2);
      n.height = std::max(1u, r.height / 2);
      n.texels.resize(std::size_t(n.width) * n.height);
      const std::uint32_t sx = r.width / n.width, sy = r.height / n.height;
      for (std::uint32_t y = 0; y < n.height; ++y)
        for (std::uint32_t x = 0; x < n.width; ++x) {
          glm::vec3 sum(0.0f);
          for (std::uint32_t j = 0; j < sy; ++j)
            for (std::uint32_t i = 0; i < sx; ++i) sum += r.at(int(x * sx + i), int(y * sy + j));
          n.texels[std::size_t(y) * n.width + x] = sum / float(sx * sy);
        }
      r = std::move(n);
    }
    return r;
  }
};

glm::vec3 direction(float u, float v) {
  const float phi = (u - 0.5f) * 2.0f * kPi, theta = v * kPi;
  return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

// Karis' prefilter with n = v = r: GGX half vectors around r, reflected, weighted by
// n.l; rougher levels read a coarser copy of the map so few samples do not alias.
std::vector<glm::vec4> prefilter(const LatLong& source) {
  constexpr std::uint32_t W = Environment::kWidth, H = Environment::kHeight, K = Environment::kLevels;
  constexpr std::uint32_t kSamples = 128;
  std::vector<glm::vec4> out(std::size_t(W) * H * K);
  for (std::uint32_t k = 0; k < K; ++k) {
    const float roughness = float(k) / float(K - 1);
    const LatLong src = source.reduced(std::max(4u, (2 * W) >> k), std::max(2u, (2 * H) >> k));
    for (std::uint32_t y = 0; y < H; ++y)
      for (std::uint32_t x = 0; x < W; ++x) {
        const glm::vec3 r = direction((float(x) + 0.5f) / float(W), (float(y) + 0.5f) / float(H));
        glm::vec3 value;
        if (k == 0) {
          value = src.lookup(r);
        } else {
          value = ggxPrefiltered(r, roughness, kSamples, [&src](const glm::vec3& l) { return src.lookup(l); });
        }
        out[(std::size_t(k) * H + y) * W + x] = glm::vec4(value, 1.0f);
      }
  }
  return out;
}
}  // namespace

Environment Environment::constant(const glm::vec3& radiance) {
  if (!finiteNonNegative(radiance)) throw Error("environment radiance must be finite and non-negative");
  Environment e;
  e.average_ = radiance;
  std::fill(e.prefiltered_.begin(), e.prefiltered_.end(), glm::vec4(radiance, 1.0f));
  return e;
}

Environment Environment::latLong(std::uint32_t width, std::uint32_t height, std::span<const glm::vec4> texels,
                                 float scale) {
  if (width == 0 || height == 0 || texels.size() != std::size_t(width) * height)
    throw Error("environment map size does not match its texels");
  if (!std::isfinite(scale) || scale < 0.0f) throw Error("environment scale must be finite and non-negative");
  glm::dvec3 sum(0.0);
  double weight = 0.0;
  LatLong map{width, height, std::vector<glm::vec3>(texels.size())};
  for (std::uint32_t y = 0; y < height; ++y) {
    // Row y spans polar angles [y, y+1] * pi / height; its solid angle is proportional to sin(theta).
    const double w = std::sin((y + 0.5) * std::numbers::pi / height);
    for (std::uint32_t x = 0; x < width; ++x) {
      const glm::vec4& t = texels[std::size_t(y) * width + x];
      if (!finiteNonNegative(glm::vec3(t))) throw Error("environment map texels must be finite and non-negative");
      map.texels[std::size_t(y) * width + x] = glm::vec3(t) * scale;
      sum += w * glm::dvec3(t);
      weight += w;
    }
  }
  Environment e;
  e.average_ = glm::vec3(sum / weight) * scale;
  e.prefiltered_ = prefilter(map);
  return e;
}

glm::vec3 Environment::radiance(const glm::vec3& d) const {
  return bilinear(kWidth, kHeight, d, [this](int x, int y) {
    x = ((x % int(kWidth)) + int(kWidth)) % int(kWidth);
    y = std::clamp(y, 0, int(kHeight) - 1);
    return glm::vec3(prefiltered_[std::size_t(y) * kWidth + std::size_t(x)]);
  });
}

Environment Environment::withFog(const Medium& fog) const {
  if (!finiteNonNegative(fog.absorption) || !finiteNonNegative(fog.scattering) || !finiteNonNegative(fog.emission))
    throw Error("fog coefficients must be finite and non-negative");
  if (!(std::abs(fog.g) < 1.0f)) throw Error("fog phase g must be in (-1, 1)");
  Environment e = *this;
  e.fog_ = fog.empty() ? std::nullopt : std::optional<Medium>(fog);
  return e;
}

}  // namespace tsr::vk
