#include "tsr/embree/denoiser.hpp"

#include "filters/denoiser_detail.hpp"
#include "filters/image_blur.hpp"
#include "filters/pixel_filter_detail.hpp"
#include "tsr/embree/error.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace tsr::embree {

namespace {

constexpr glm::vec3 kLuma{0.2126f, 0.7152f, 0.0722f};
// B3-spline taps of the a-trous wavelet, 1 4 6 4 1 / 16.
constexpr float kTaps[5] = {1.0f / 16, 1.0f / 4, 3.0f / 8, 1.0f / 4, 1.0f / 16};
constexpr float kMinAlbedo = detail::kMinDenoiseAlbedo;

glm::vec3 finiteOr0(const glm::vec3& v) {
  return {std::isfinite(v.x) ? v.x : 0.0f, std::isfinite(v.y) ? v.y : 0.0f, std::isfinite(v.z) ? v.z : 0.0f};
}

struct Guide {
  std::vector<glm::vec3> normal;  // unit, or zero where there is none
  std::vector<float> depth;       // +inf where nothing was hit
  std::vector<float> slope;       // depth change per pixel step, the larger of x and y
};

Guide guideOf(const DenoiseInput& in) {
  const int w = int(in.width), h = int(in.height);
  const std::size_t n = std::size_t(w) * h;
  Guide g;
  g.normal.resize(n);
  g.depth.resize(n);
  g.slope.assign(n, 0.0f);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec3 m = finiteOr0(in.normal[i]);
    const float l = glm::length(m);
    g.normal[i] = l > 1e-3f ? m / l : glm::vec3(0.0f);
    g.depth[i] = std::isfinite(in.depth[i]) ? in.depth[i] : std::numeric_limits<float>::infinity();
  }
  auto at = [&](int x, int y) { return g.depth[std::size_t(y) * w + x]; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float z = at(x, y);
      if (!std::isfinite(z)) continue;
      float s = 0.0f;
      // One-sided where a neighbour is missing or shows nothing.
      for (auto [dx, dy] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
        const int nx = x + dx, ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
        const float zn = at(nx, ny);
        if (std::isfinite(zn)) s = std::max(s, std::abs(zn - z));
      }
      g.slope[std::size_t(y) * w + x] = s;
    }
  return g;
}

void check(const DenoiseInput& in, const DenoiseSettings& s) {
  const std::size_t n = std::size_t(in.width) * in.height;
  if (n == 0) throw Error("denoiser: the image is empty");
  auto size = [&](std::size_t got, const char* what) {
    if (got != n)
      throw Error(std::string("denoiser: ") + what + " has " + std::to_string(got) + " pixels, the image " +
                  std::to_string(n));
  };
  size(in.colour.size(), "colour");
  size(in.variance.size(), "variance");
  size(in.albedo.size(), "albedo");
  size(in.normal.size(), "normal");
  size(in.depth.size(), "depth");
  if (!in.emitted.empty()) size(in.emitted.size(), "emitted");
  if (s.method == DenoiseMethod::Regression) {
    size(in.firstHalf.size(), "firstHalf");
    size(in.firstHalfShare.size(), "firstHalfShare");
    if (s.radius < 1 || s.radius > 32) throw Error("denoiser: radius must be 1 to 32");
    if (s.patchRadius > 8) throw Error("denoiser: patchRadius must be 0 to 8");
  }
  if (s.levels < 1 || s.levels > 10) throw Error("denoiser: levels must be 1 to 10");
  if (!(s.sigmaLuminance > 0.0f) || !(s.sigmaNormal >= 0.0f) || !(s.sigmaDepth > 0.0f))
    throw Error("denoiser: sigmaLuminance and sigmaDepth must be > 0, sigmaNormal >= 0");
}

}  // namespace

std::vector<glm::vec3> denoise(const DenoiseInput& in, const DenoiseSettings& s) {
  check(in, s);
  auto run = [&](const DenoiseInput& input) {
    return s.method == DenoiseMethod::Regression ? detail::regressionDenoise(input, s)
                                                 : detail::atrousDenoise(input, s);
  };
  if (in.emitted.empty()) return run(in);
  std::vector<glm::vec3> scattered(in.colour.size());
  for (std::size_t i = 0; i < scattered.size(); ++i) scattered[i] = in.colour[i] - finiteOr0(in.emitted[i]);
  DenoiseInput without = in;
  without.colour = scattered;
  std::vector<glm::vec3> out = run(without);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] += finiteOr0(in.emitted[i]);
  return out;
}

std::vector<glm::vec3> detail::atrousDenoise(const DenoiseInput& in, const DenoiseSettings& s) {
  const int w = int(in.width), h = int(in.height);
  const std::size_t n = std::size_t(w) * h;
  const Guide g = guideOf(in);

  // Demodulated: what lights the first surface, flat over a texture.
  std::vector<glm::vec3> modulation(n), c(n), next(n);
  std::vector<float> v(n), nextV(n);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec3 a = finiteOr0(in.albedo[i]);
    modulation[i] = glm::max(a, glm::vec3(kMinAlbedo));
    c[i] = finiteOr0(in.colour[i]) / modulation[i];
    const glm::vec3 var = glm::max(finiteOr0(in.variance[i]), glm::vec3(0.0f)) / (modulation[i] * modulation[i]);
    // Var[lum] <= sum_c w_c Var_c for any correlation of the channels.
    v[i] = glm::dot(kLuma, var);
  }

  for (unsigned level = 0; level < s.levels; ++level) {
    const int step = 1 << level;
    const std::vector<float> sigmaV = pf::blur121(v, w, h, s.threads);
    pf::parallelRows(s.threads, h, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y)
        for (int x = 0; x < w; ++x) {
          const std::size_t i = std::size_t(y) * w + x;
          const float li = glm::dot(kLuma, c[i]);
          const float zi = g.depth[i];
          const glm::vec3 ni = g.normal[i];
          glm::vec3 sum(0.0f);
          float sumV = 0.0f, weights = 0.0f;
          for (int ky = 0; ky < 5; ++ky) {
            const int ny = y + (ky - 2) * step;
            if (ny < 0 || ny >= h) continue;
            for (int kx = 0; kx < 5; ++kx) {
              const int nx = x + (kx - 2) * step;
              if (nx < 0 || nx >= w) continue;
              const std::size_t j = std::size_t(ny) * w + nx;
              float wgt = kTaps[kx] * kTaps[ky];
              if (j != i) {
                const float zj = g.depth[j];
                if (std::isfinite(zi) != std::isfinite(zj)) continue;  // surface and background never mix
                if (std::isfinite(zi)) {
                  const float reach =
                      s.sigmaDepth * g.slope[i] * float(step * std::max(std::abs(kx - 2), std::abs(ky - 2)));
                  wgt *= std::exp(-std::abs(zi - zj) / (reach + 1e-3f * std::abs(zi) + 1e-6f));
                  const float cosine = std::max(0.0f, glm::dot(ni, g.normal[j]));
                  wgt *= std::pow(cosine, s.sigmaNormal);
                }
                // In standard errors of the less noisy of the two: a highlight
                // (a step many of its neighbours' errors high) stays apart
                // even when its own samples are noisy.
                const float error = std::sqrt(std::max(std::min(sigmaV[i], sigmaV[j]), 0.0f));
                wgt *= std::exp(-std::abs(li - glm::dot(kLuma, c[j])) / (s.sigmaLuminance * error + 1e-10f));
              }
              sum += wgt * c[j];
              sumV += wgt * wgt * v[j];
              weights += wgt;
            }
          }
          next[i] = sum / weights;
          nextV[i] = sumV / (weights * weights);
        }
    });
    std::swap(c, next);
    std::swap(v, nextV);
  }

  std::vector<glm::vec3> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = c[i] * modulation[i];
  return out;
}

}  // namespace tsr::embree
