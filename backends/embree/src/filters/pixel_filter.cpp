#include "tsr/embree/pixel_filter.hpp"

#include "filters/image_blur.hpp"
#include "filters/pixel_filter_detail.hpp"
#include "tsr/embree/error.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace tsr::embree {

namespace {

constexpr glm::vec3 kLuma{0.2126f, 0.7152f, 0.0722f};

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// NaN or inf samples would poison every neighbour of the pixel: read as 0.
glm::vec3 sane(const glm::vec3& v) { return finite(v) ? v : glm::vec3(0.0f); }

void checkSize(std::size_t got, std::size_t want, const char* name) {
  if (got != want)
    throw Error(std::string("pixel filter: ") + name + " has " + std::to_string(got) +
                " entries, expected width*height = " + std::to_string(want));
}

std::size_t checkInput(const PixelFilterInput& in) {
  if (in.width == 0 || in.height == 0) throw Error("pixel filter: empty image");
  if (in.width > 1u << 15 || in.height > 1u << 15) throw Error("pixel filter: image wider or taller than 32768 pixels");
  const std::size_t n = std::size_t(in.width) * in.height;
  checkSize(in.highVariance.size(), n, "highVariance");
  checkSize(in.highVarianceVar.size(), n, "highVarianceVar");
  checkSize(in.lowVariance.size(), n, "lowVariance");
  checkSize(in.rangeColour.size(), n, "rangeColour");
  checkSize(in.rangeDepth.size(), n, "rangeDepth");
  if (!in.rangeSpread.empty()) checkSize(in.rangeSpread.size(), n, "rangeSpread");
  return n;
}

void checkSettings(const PixelFilterSettings& s) {
  if (!(s.sigmaS > 0.0f && s.sigmaS <= 1e4f)) throw Error("pixel filter: sigmaS must be in (0, 1e4] pixels");
  if (!(s.sigmaC >= 1e-6f)) throw Error("pixel filter: sigmaC must be at least 1e-6");
  if (!(s.sigmaD >= 1e-6f)) throw Error("pixel filter: sigmaD must be at least 1e-6 (infinity ignores depth)");
  if (!(s.threshold >= 0.0f)) throw Error("pixel filter: threshold must be >= 0");
  if (!(s.minBackground > 0.0f)) throw Error("pixel filter: minBackground must be positive");
  if (s.iterations < 1 || s.iterations > 8) throw Error("pixel filter: iterations must be in [1, 8]");
  if (s.adaptiveWidth && !(s.adaptiveTarget > 0.0f)) throw Error("pixel filter: adaptiveTarget must be positive");
}

pf::Range scaledRange(const PixelFilterInput& in, const PixelFilterSettings& s, std::size_t n) {
  pf::Range r;
  r.r.resize(n);
  r.g.resize(n);
  r.b.resize(n);
  r.d.resize(n);
  r.e.resize(n);
  const float kc = 1.0f / (std::sqrt(2.0f) * s.sigmaC);
  const float kd = std::isfinite(s.sigmaD) ? 1.0f / (std::sqrt(2.0f) * s.sigmaD) : 0.0f;
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec3 c = glm::clamp(sane(in.rangeColour[i]) * kc, -pf::kMaxScaledDepth, pf::kMaxScaledDepth);
    r.r[i] = c.x;
    r.g[i] = c.y;
    r.b[i] = c.z;
    const float d = in.rangeDepth[i];
    r.d[i] = std::isfinite(d) ? std::clamp(d * kd, -pf::kMaxScaledDepth, pf::kMaxScaledDepth) : pf::kBackground;
    const float e = in.rangeSpread.empty() ? 0.0f : in.rangeSpread[i];
    r.e[i] = std::isfinite(e) ? std::clamp(e * kc, 0.0f, pf::kMaxScaledDepth) : 0.0f;
  }
  return r;
}

// 3.15-3.17: the box extent e that would bring u down to the target f,
// sigma = 1.5 e, clamped to [g, c g] above the guide g = sigmaS / sqrt(n),
// c = 4, and never wider than sigmaS. The paper's lower end g/c left
// pixels whose few samples happened to agree a kernel under a pixel: at
// 8 spp in a room lit only indirectly, dark dots all over the walls. u is
// estimated before filtering from 5x5 box means of the variance and of Lu
// (Lb = lum(mean Lu + Llv)).
pf::Plane adaptiveSigma(const PixelFilterInput& in, const PixelFilterSettings& s, const pf::State& st) {
  const int w = int(in.width), h = int(in.height);
  const std::size_t n = st.v.size();
  pf::Plane lum(n);
  for (std::size_t i = 0; i < n; ++i) lum[i] = kLuma.x * st.lr[i] + kLuma.y * st.lg[i] + kLuma.z * st.lb[i];
  const pf::Plane meanVar = pf::boxMean(st.v, w, h, 2);
  const pf::Plane meanLum = pf::boxMean(lum, w, h, 2);
  constexpr float c = 4.0f;
  const float guide = s.sigmaS / std::sqrt(float(std::max(in.samples, 1u)));
  const float lo = guide, hi = std::min(guide * c, s.sigmaS);
  const float target = s.adaptiveTarget * s.threshold;
  pf::Plane sigma(n);
  for (std::size_t i = 0; i < n; ++i) {
    const float lb = std::max(meanLum[i] + luminance(sane(in.lowVariance[i])), s.minBackground);
    const float u = meanVar[i] / (lb * lb);
    // No variance around a pixel after a few samples is no evidence that it
    // converged (where light comes by rare paths, all of them were 0): it
    // gets the widest kernel, as at the first frames, not the narrowest,
    // which left it its own black samples.
    float sg = hi;
    if (target > 0.0f && meanVar[i] > 0.0f) sg = 1.5f * std::max(0.0f, 0.5f * std::sqrt(u / target) - 0.5f);
    sigma[i] = std::clamp(sg, std::min(lo, hi), hi);
  }
  return sigma;
}

// Pixels that mix two surfaces (3.6.5's antialiased pixels, in 2-D and for
// every kernel). The spread keeps them out of every kernel, and a line of
// them along a silhouette gathers only itself, so they would show their
// own few samples: at low spp in a dim room mostly zero, a dotted dark
// outline along every silhouette. Instead each is modelled as coverage a
// of one side and 1 - a of the other: of the four pairs of neighbours
// opposite each other across it (at distance 1 or 2), the pair whose range
// colours differ most and between which its own range colour lies
// (projected onto the segment, fit exp(-b^2), as in 3.19-3.20) gives the
// sides, and the pixel takes their filtered values mixed by a, and by the
// fit with its own. A pixel is taken for mixed when its flash samples
// disagree (spread), or when such a pair brackets it strictly (a within
// [0.1, 0.9]): a silhouette pixel whose few flash samples agreed by chance
// has a mixed colour too. A mixed pixel that no pair brackets (two
// surfaces of one colour, a corner of three) takes the filtered value of
// its purer neighbour nearest in range colour: at worst an edge shifted by
// a pixel.
void recoverMixedPixels(const pf::Image& im, const pf::Range& rg, pf::State& st, pf::Plane& r, int threads) {
  constexpr float kDisagree = 1.0f;  // scaled spread^2 above this: the flash samples disagree
  constexpr float kDistinct = 1.0f;  // scaled squared colour distance of two sides that differ
  constexpr float kBetween = 0.1f;   // coverage kept from either end for a pixel the spread calls pure
  const int w = im.w, h = im.h;
  struct Filtered {
    pf::Plane lr, lg, lb, v;
  } const in{st.lr, st.lg, st.lb, st.v};  // the kernel's output, read while st is rewritten
  const pf::Plane rIn = r;
  pf::parallelRows(threads, h, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t j = std::size_t(y) * w + x;
        const bool disagree = rg.e[j] * rg.e[j] > kDisagree;
        const glm::vec3 cj(rg.r[j], rg.g[j], rg.b[j]);
        float bestScore = 0.0f, bestCover = 0.0f, bestFit = 0.0f;
        std::size_t bestA = j, bestB = j;
        float nearest = std::numeric_limits<float>::infinity();
        std::size_t nearestAt = j;
        for (int dist = 1; dist <= 2; ++dist)
          for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}, std::pair{1, 1}, std::pair{1, -1}}) {
            const int ax = x - dist * dx, ay = y - dist * dy, bx = x + dist * dx, by = y + dist * dy;
            if (ax < 0 || ax >= w || ay < 0 || ay >= h || bx < 0 || bx >= w || by < 0 || by >= h) continue;
            const std::size_t a = std::size_t(ay) * w + ax, b = std::size_t(by) * w + bx;
            // A side must be purer than the pixel itself.
            if (rg.e[a] > rg.e[j] || rg.e[b] > rg.e[j]) continue;
            const glm::vec3 ca(rg.r[a], rg.g[a], rg.b[a]), cb(rg.r[b], rg.g[b], rg.b[b]);
            for (const auto& [k, ck] : {std::pair{a, ca}, std::pair{b, cb}}) {
              const glm::vec3 dk = ck - cj;
              if (glm::dot(dk, dk) < nearest) nearest = glm::dot(dk, dk), nearestAt = k;
            }
            const glm::vec3 g = cb - ca;
            const float gg = glm::dot(g, g);
            if (gg <= kDistinct) continue;  // both sides alike: not an edge across this pair
            const float cover = std::clamp(glm::dot(cj - ca, g) / gg, 0.0f, 1.0f);
            if (!disagree && (cover < kBetween || cover > 1.0f - kBetween)) continue;
            const glm::vec3 off = cj - ca - cover * g;
            const float fit = std::exp(-glm::dot(off, off));
            const float score = gg * fit;
            if (score > bestScore) bestScore = score, bestCover = cover, bestFit = fit, bestA = a, bestB = b;
          }
        if (bestA == j) {
          if (!disagree || nearestAt == j) continue;
          bestA = bestB = nearestAt;
          bestFit = 1.0f;
        }
        const float ka = bestFit * (1.0f - bestCover), kb = bestFit * bestCover, kj = 1.0f - bestFit;
        st.lr[j] = ka * in.lr[bestA] + kb * in.lr[bestB] + kj * in.lr[j];
        st.lg[j] = ka * in.lg[bestA] + kb * in.lg[bestB] + kj * in.lg[j];
        st.lb[j] = ka * in.lb[bestA] + kb * in.lb[bestB] + kj * in.lb[j];
        const float va = in.v[bestA], vb = in.v[bestB], vj = in.v[j];
        st.v[j] = (ka * va + kb * vb + kj * vj);
        // Var[Lf] of the mix, the three filtered values taken as independent.
        const float varF = ka * ka * rIn[bestA] * va + kb * kb * rIn[bestB] * vb + kj * kj * rIn[j] * vj;
        r[j] = st.v[j] > 0.0f ? std::clamp(varF / st.v[j], 1e-6f, 1.0f) : rIn[j];
      }
  });
}

}  // namespace

float luminance(const glm::vec3& c) { return glm::dot(kLuma, c); }

float blendFactor(float u, float f, float t) {
  if (!(u >= 0.0f) || !std::isfinite(u)) return 0.0f;  // no trustworthy variance: filtered only
  if (u <= t) return 1.0f;                             // case 2 (also u = f = 0)
  const float d = t * u + t * f - u * f;
  if (!(d >= 0.0f)) return 0.0f;                                // case 1 (also t = 0, u > 0)
  return std::clamp((f + std::sqrt(d)) / (u + f), 0.0f, 1.0f);  // case 3, 3.12
}

bool isFilterFrame(std::uint32_t frame) { return frame >= 4 && (frame & (frame - 1)) == 0; }

FilteredBuffer filterHighVariance(const PixelFilterInput& in, const PixelFilterSettings& settings) {
  const std::size_t n = checkInput(in);
  checkSettings(settings);
  const pf::Image im{int(in.width), int(in.height)};
  const pf::Range range = scaledRange(in, settings, n);

  pf::State st;
  st.lr.resize(n);
  st.lg.resize(n);
  st.lb.resize(n);
  st.v.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec3 l = sane(in.highVariance[i]);
    st.lr[i] = l.x;
    st.lg[i] = l.y;
    st.lb[i] = l.z;
    // Var[lum] <= sum_c w_c Var_c for any correlation between channels
    // (Cauchy-Schwarz, sum w_c = 1): a conservative scalar.
    st.v[i] = std::max(0.0f, luminance(sane(in.highVarianceVar[i])));
  }
  st.mx.assign(n, 0.0f);
  st.vx.assign(n, 0.0f);
  st.my.assign(n, 0.0f);
  st.vy.assign(n, 0.0f);
  st.q.assign(n, 1.0f);

  pf::Plane sigma = settings.adaptiveWidth ? adaptiveSigma(in, settings, st) : pf::Plane(n, settings.sigmaS);
  const pf::KernelParams params{settings.threads, settings.iterations, settings.antialiasRecovery};
  pf::Plane r;
  switch (settings.kernel) {
    case FilterKernel::Bilateral:
      pf::bilateral(im, range, sigma, st, r, params);
      break;
    case FilterKernel::Separable:
      pf::separable(im, range, sigma, st, r, params);
      break;
    case FilterKernel::Atrous:
      pf::atrous(im, range, sigma, st, r, params);
      break;
  }
  if (!in.rangeSpread.empty()) recoverMixedPixels(im, range, st, r, settings.threads);

  FilteredBuffer out;
  out.width = in.width;
  out.height = in.height;
  out.samples = in.samples;
  out.radiance.resize(n);
  for (std::size_t i = 0; i < n; ++i) out.radiance[i] = glm::vec3(st.lr[i], st.lg[i], st.lb[i]);
  out.variance = std::move(st.v);
  out.reduction = std::move(r);
  out.sigma = std::move(sigma);
  return out;
}

BlendResult blend(const PixelFilterInput& in, const FilteredBuffer& fb, const PixelFilterSettings& settings) {
  const std::size_t n = checkInput(in);
  checkSettings(settings);
  if (fb.width != in.width || fb.height != in.height) throw Error("pixel filter: filtered buffer has another size");
  checkSize(fb.radiance.size(), n, "filtered radiance");
  checkSize(fb.variance.size(), n, "filtered variance");
  checkSize(fb.reduction.size(), n, "filtered reduction");
  // The filtered buffer may be older than Lu: Var[Lu] scales as 1/n, while Lf
  // keeps the variance it had when it was filtered.
  const float age = (fb.samples > 0 && in.samples > 0) ? float(fb.samples) / float(in.samples) : 1.0f;
  const float t = settings.threshold;
  // 3.18's c = 2 is right for a few samples; kept fixed, its clamp biased
  // every pixel whose blend stays below 1 (caustics, rooms lit only
  // indirectly) at 1024 spp as much as at 8. Widened as the standard error
  // shrinks, it removes the spikes of a preview and lets go as it converges.
  const float spikeBound = 2.0f * std::sqrt(std::max(1.0f, float(in.samples) / 8.0f));
  BlendResult out;
  out.radiance.resize(n);
  out.blendFactor.resize(n);
  pf::parallelRows(settings.threads, int(in.height), [&](int y0, int y1) {
    for (std::size_t i = std::size_t(y0) * in.width; i < std::size_t(y1) * in.width; ++i) {
      const glm::vec3 lf = fb.radiance[i];
      const glm::vec3 llv = sane(in.lowVariance[i]);
      glm::vec3 lu = sane(in.highVariance[i]);
      const float lb = std::max(luminance(lf + llv), settings.minBackground);  // 3.10
      const float varF = fb.reduction[i] * fb.variance[i];                     // 3.5
      const float u = fb.variance[i] * age / (lb * lb);
      const float f = varF / (lb * lb);
      const float s = blendFactor(u, f, t);
      // 3.18, c = 2, only while the filtered buffer is blended in: once the
      // unfiltered pixel meets the threshold (s = 1) it is shown as it is,
      // or the clamp's bias would never vanish.
      if (settings.spikeRemoval && s < 1.0f) lu = glm::clamp(lu, lf / spikeBound, spikeBound * lf);
      out.radiance[i] = llv + s * lu + (1.0f - s) * lf;  // 3.1
      out.blendFactor[i] = s;
    }
  });
  return out;
}

}  // namespace tsr::embree
