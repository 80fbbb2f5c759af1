// The regression method of the whole-image denoiser (denoiser.hpp): NFOR's
// collaborative first-order regression with non-local-means weights,
// cross-filtered between the two halves of each pixel's samples; per pixel
// the unfiltered mean or one of two strengths, whichever has the least
// error estimated from the halves.
#include "filters/denoiser_detail.hpp"
#include "filters/image_blur.hpp"
#include "filters/pixel_filter_detail.hpp"

#include <Eigen/Dense>
#include <glm/common.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

namespace tsr::embree::detail {

namespace {

// Regression unknowns per channel: the intercept and slopes along x, y, the
// normal's three components and depth.
constexpr int kUnknowns = 7;
constexpr int kMoments = kUnknowns * (kUnknowns + 1) / 2;
// Ridge on the slopes, relative to the window's weight once each feature is
// scaled to unit spread: keeps a fit stable where a feature barely varies.
constexpr float kRidge = 1e-2f;
// NFOR's two strengths (k of the non-local-means distance).
constexpr std::array<float, 2> kStrengths = {0.5f, 1.0f};
// How far the estimated errors are averaged before each pixel picks.
constexpr int kErrorRadius = 3;
// The unfiltered mean's estimated error counts twice: it comes from the
// same two halves that judge it, so where they agree by chance it is too
// low, and lone unfiltered pixels were left as speckles among filtered
// ones (the Cornell box's ceiling, the frosted sphere).
constexpr float kRawPenalty = 2.0f;

using Plane = std::vector<float>;
using Planes = std::array<Plane, 3>;

// Rows per band (the unit of parallel work) and pixels per chunk of a row
// (the regression's sums of one chunk stay in the L1 cache).
constexpr int kBandRows = 16;
constexpr int kChunk = 32;

// The images the regression reads, padded by radius + patch pixels on every
// side so windows and patches read without bounds checks.
struct Setup {
  int w = 0, h = 0, radius = 0, patch = 0, threads = 0;
  int pad = 0, pw = 0;             // padding and padded width
  Plane nx, ny, nz, z;             // features (padded, 0 outside; z = 0 where nothing was hit)
  Plane hit;                       // 1 surface, 0 background, -1 outside: surface and background never mix
  std::array<Planes, 2> half;      // demodulated means of the halves (padded by replication)
  std::array<Planes, 2> guideVar;  // their variance (padded by replication)
  std::array<Planes, 2> halfVar;   // each pixel's own estimate (not blurred, not padded)
  std::vector<glm::vec3> modulation;
  std::vector<float> share;  // the first half's share of the samples

  std::size_t at(int x, int y) const { return std::size_t(y) * w + x; }
  std::size_t padded(int x, int y) const { return std::size_t(y + pad) * pw + (x + pad); }
  // The padded copy of an image; outside it is `outside`, or the nearest
  // edge pixel when `outside` is not given.
  Plane padOf(const Plane& v, std::optional<float> outside = std::nullopt) const {
    Plane out(std::size_t(pw) * (h + 2 * pad), outside.value_or(0.0f));
    for (int y = -pad; y < h + pad; ++y)
      for (int x = -pad; x < w + pad; ++x) {
        const bool inside = x >= 0 && y >= 0 && x < w && y < h;
        if (inside || !outside) out[padded(x, y)] = v[at(std::clamp(x, 0, w - 1), std::clamp(y, 0, h - 1))];
      }
    return out;
  }
};

float finiteOr0(float v) { return std::isfinite(v) ? v : 0.0f; }

Setup setupOf(const DenoiseInput& in, const DenoiseSettings& settings) {
  Setup s;
  s.w = int(in.width);
  s.h = int(in.height);
  s.radius = int(settings.radius);
  s.patch = int(settings.patchRadius);
  s.threads = settings.threads;
  s.pad = s.radius + s.patch;
  s.pw = s.w + 2 * s.pad;
  const std::size_t n = std::size_t(s.w) * s.h;
  Plane nx(n), ny(n), nz(n), z(n), hit(n);
  std::array<Planes, 2> half;
  s.modulation.resize(n);
  s.share.resize(n);
  for (int k = 0; k < 2; ++k)
    for (int c = 0; c < 3; ++c) {
      half[k][c].resize(n);
      s.halfVar[k][c].resize(n);
    }
  for (std::size_t i = 0; i < n; ++i) {
    glm::vec3 normal(finiteOr0(in.normal[i].x), finiteOr0(in.normal[i].y), finiteOr0(in.normal[i].z));
    const float l = std::sqrt(normal.x * normal.x + normal.y * normal.y + normal.z * normal.z);
    if (l > 1e-3f) normal /= l;
    nx[i] = normal.x;
    ny[i] = normal.y;
    nz[i] = normal.z;
    hit[i] = std::isfinite(in.depth[i]) ? 1.0f : 0.0f;
    z[i] = hit[i] > 0.0f ? in.depth[i] : 0.0f;
    const glm::vec3 a(finiteOr0(in.albedo[i].x), finiteOr0(in.albedo[i].y), finiteOr0(in.albedo[i].z));
    s.modulation[i] = glm::max(a, glm::vec3(kMinDenoiseAlbedo));
    // Without halves (a single sample) both halves are the pixel.
    const float share = std::clamp(finiteOr0(in.firstHalfShare[i]), 0.0f, 1.0f);
    const bool split = share > 0.0f && share < 1.0f;
    s.share[i] = split ? share : 0.5f;
    for (int c = 0; c < 3; ++c) {
      const float m = s.modulation[i][c];
      const float mean = finiteOr0(in.colour[i][c]) / m;
      const float first = split ? finiteOr0(in.firstHalf[i][c]) / m : mean;
      const float second = split ? (mean - share * first) / (1.0f - share) : mean;
      // Each half's variance from the halves' difference: Var(A - B) =
      // vA + vB, vA = sigma^2 / (share N), vB = sigma^2 / ((1 - share) N).
      // Not the samples' variance over N: stratified samples make the mean
      // far better than that where a pixel straddles an edge, and that
      // over-estimate let edges and small lights melt into their surroundings.
      const float diff2 = (first - second) * (first - second);
      half[0][c][i] = first;
      half[1][c][i] = second;
      s.halfVar[0][c][i] = diff2 * (1.0f - s.share[i]);
      s.halfVar[1][c][i] = diff2 * s.share[i];
    }
  }
  s.nx = s.padOf(nx, 0.0f);
  s.ny = s.padOf(ny, 0.0f);
  s.nz = s.padOf(nz, 0.0f);
  s.z = s.padOf(z, 0.0f);
  s.hit = s.padOf(hit, -1.0f);
  // One pixel's difference is a one-sample estimate: averaged over 3x3 for
  // the weights. The error estimates keep each pixel's own (unbiased where
  // the blurred one is not: a spike's variance spread over nine pixels
  // counted the spike as the filter's error, and the unfiltered pixel won
  // around every bright sample, leaving speckles).
  for (int k = 0; k < 2; ++k)
    for (int c = 0; c < 3; ++c) {
      s.half[k][c] = s.padOf(half[k][c]);
      s.guideVar[k][c] = s.padOf(pf::blur121(s.halfVar[k][c], s.w, s.h, s.threads));
    }
  return s;
}

// Non-local-means weights w(i, i + o) of the centres i in rows [y0, y1),
// written to out[(y - y0) * w + x]: patches of the guide image u compared
// in units of their variance v (Rousselle et al. 2012), strength k2 = k^2;
// zero where i + o is outside the image or mixes surface and background.
class OffsetWeights {
 public:
  explicit OffsetWeights(const Setup& s) : s_(s) {}

  void compute(const Planes& u, const Planes& v, int ox, int oy, float k2, int y0, int y1, float* out) {
    const int w = s_.w, f = s_.patch;
    const int rows = y1 - y0 + 2 * f, cols = w + 2 * f;
    const std::ptrdiff_t shift = std::ptrdiff_t(oy) * s_.pw + ox;
    distance_.assign(std::size_t(rows) * cols, 0.0f);
    for (int r = 0; r < rows; ++r) {
      float* d = &distance_[std::size_t(r) * cols];
      const std::size_t p0 = s_.padded(-f, y0 - f + r);
      for (int c = 0; c < 3; ++c) {
        const float* uc = u[c].data() + p0;
        const float* vc = v[c].data() + p0;
        for (int x = 0; x < cols; ++x) {
          const float vp = vc[x], vq = vc[x + shift], diff = uc[x] - uc[x + shift];
          d[x] += (diff * diff - (vp + std::min(vp, vq))) / (1e-10f + k2 * (vp + vq));
        }
      }
    }
    column_.resize(cols);
    const float norm = 1.0f / float(3 * (2 * f + 1) * (2 * f + 1));
    for (int y = y0; y < y1; ++y) {
      std::fill(column_.begin(), column_.end(), 0.0f);
      for (int r = y - y0; r <= y - y0 + 2 * f; ++r) {
        const float* d = &distance_[std::size_t(r) * cols];
        for (int x = 0; x < cols; ++x) column_[x] += d[x];
      }
      float* o = out + std::size_t(y - y0) * w;
      float sum = 0.0f;
      for (int k = 0; k < 2 * f; ++k) sum += column_[k];
      for (int x = 0; x < w; ++x) {
        sum += column_[x + 2 * f];
        o[x] = sum;
        sum -= column_[x];
      }
      // Eigen's exp runs on SIMD lanes (the weights are most of the cost).
      Eigen::Map<Eigen::ArrayXf> row(o, w);
      row = (-(row * norm).max(0.0f)).exp();
      const float* hi = s_.hit.data() + s_.padded(0, y);
      for (int x = 0; x < w; ++x) o[x] = hi[x] == hi[x + shift] ? o[x] : 0.0f;
    }
  }

 private:
  const Setup& s_;
  std::vector<float> distance_, column_;
};

// One band's share of the collaborative sum: rows [y0 - r, y1 + r) of the
// image widened by r on each side; channels 0-2 the weighted fits, 3 the
// weights.
struct BandSum {
  int y0 = 0, rows = 0, width = 0;
  std::array<Plane, 4> sum;
};

// The regression of one chunk of pixels (row y, columns [x0, x0 + n)): the
// weighted sums of the features' products over the window, and per pixel
// the fitted coefficients beta[p * 3 + c][k].
struct ChunkFit {
  float x[kUnknowns][kChunk];
  float moments[kMoments][kChunk];
  float rhs[kUnknowns * 3][kChunk];
  float beta[kUnknowns * 3][kChunk];

  // The features of the neighbours i + (ox, oy) as seen from the centres i.
  void features(const Setup& s, std::size_t i0, std::ptrdiff_t shift, int ox, int oy, int n) {
    for (int k = 0; k < n; ++k) {
      const std::size_t i = i0 + k, j = i + shift;
      x[0][k] = 1.0f;
      x[1][k] = float(ox);
      x[2][k] = float(oy);
      x[3][k] = s.nx[j] - s.nx[i];
      x[4][k] = s.ny[j] - s.ny[i];
      x[5][k] = s.nz[j] - s.nz[i];
      x[6][k] = s.z[j] - s.z[i];
    }
  }
};

// Filters `target` with weights from `guide` (variance guideVar); returns
// the demodulated result.
Planes regress(const Setup& s, const Planes& target, const Planes& guide, const Planes& guideVar, float k) {
  const int w = s.w, h = s.h, r = s.radius, side = 2 * r + 1;
  const int bands = (h + kBandRows - 1) / kBandRows;
  std::vector<BandSum> sums(bands);

  pf::parallelRows(s.threads, bands, [&](int b0, int b1) {
    OffsetWeights weights(s);
    std::vector<float> wgt;
    ChunkFit fit;
    using Matrix = Eigen::Matrix<float, kUnknowns, kUnknowns>;
    using Rhs = Eigen::Matrix<float, kUnknowns, 3>;
    for (int b = b0; b < b1; ++b) {
      const int y0 = b * kBandRows, y1 = std::min(h, y0 + kBandRows), rows = y1 - y0;
      const std::size_t plane = std::size_t(rows) * w;
      wgt.resize(plane * side * side);
      for (int oy = -r; oy <= r; ++oy)
        for (int ox = -r; ox <= r; ++ox)
          weights.compute(guide, guideVar, ox, oy, k * k, y0, y1, &wgt[plane * std::size_t((oy + r) * side + ox + r)]);
      BandSum& out = sums[b];
      out.y0 = y0;
      out.rows = rows + 2 * r;
      out.width = w + 2 * r;
      for (Plane& p : out.sum) p.assign(std::size_t(out.rows) * out.width, 0.0f);

      for (int y = y0; y < y1; ++y)
        for (int x0 = 0; x0 < w; x0 += kChunk) {
          const int n = std::min(kChunk, w - x0);
          const std::size_t i0 = s.padded(x0, y);
          for (auto& m : fit.moments) std::fill_n(m, n, 0.0f);
          for (auto& m : fit.rhs) std::fill_n(m, n, 0.0f);
          for (int oy = -r; oy <= r; ++oy)
            for (int ox = -r; ox <= r; ++ox) {
              const float* wo = &wgt[plane * std::size_t((oy + r) * side + ox + r) + std::size_t(y - y0) * w + x0];
              const std::ptrdiff_t shift = std::ptrdiff_t(oy) * s.pw + ox;
              fit.features(s, i0, shift, ox, oy, n);
              float wx[kUnknowns][kChunk];
              for (int a = 0; a < kUnknowns; ++a)
                for (int q = 0; q < n; ++q) wx[a][q] = wo[q] * fit.x[a][q];
              for (int a = 0, idx = 0; a < kUnknowns; ++a)
                for (int bb = a; bb < kUnknowns; ++bb, ++idx)
                  for (int q = 0; q < n; ++q) fit.moments[idx][q] += wx[a][q] * fit.x[bb][q];
              for (int c = 0; c < 3; ++c) {
                const float* t = target[c].data() + i0 + shift;
                for (int a = 0; a < kUnknowns; ++a)
                  for (int q = 0; q < n; ++q) fit.rhs[a * 3 + c][q] += wx[a][q] * t[q];
              }
            }
          for (int q = 0; q < n; ++q) {
            Matrix a;
            for (int p = 0, idx = 0; p < kUnknowns; ++p)
              for (int pp = p; pp < kUnknowns; ++pp) a(p, pp) = a(pp, p) = fit.moments[idx++][q];
            Rhs rb;
            for (int p = 0; p < kUnknowns; ++p)
              for (int c = 0; c < 3; ++c) rb(p, c) = fit.rhs[p * 3 + c][q];
            // Each slope's feature scaled to unit weighted spread, then a ridge.
            Eigen::Matrix<float, kUnknowns, 1> scale;
            scale(0) = 1.0f;
            for (int p = 1; p < kUnknowns; ++p) {
              const float spread = std::sqrt(std::max(a(p, p), 0.0f) / a(0, 0));
              scale(p) = spread > 1e-6f ? 1.0f / spread : 0.0f;
            }
            Matrix scaled = scale.asDiagonal() * a * scale.asDiagonal();
            for (int p = 1; p < kUnknowns; ++p) scaled(p, p) += kRidge * a(0, 0);
            const Rhs solved = scale.asDiagonal() * scaled.ldlt().solve(scale.asDiagonal() * rb);
            for (int p = 0; p < kUnknowns; ++p)
              for (int c = 0; c < 3; ++c) fit.beta[p * 3 + c][q] = solved(p, c);
          }
          // Collaborative: every pixel of the window gets this window's fit,
          // weighted as the window weighted it.
          for (int oy = -r; oy <= r; ++oy)
            for (int ox = -r; ox <= r; ++ox) {
              const float* wo = &wgt[plane * std::size_t((oy + r) * side + ox + r) + std::size_t(y - y0) * w + x0];
              const std::ptrdiff_t shift = std::ptrdiff_t(oy) * s.pw + ox;
              fit.features(s, i0, shift, ox, oy, n);
              const std::size_t o0 = std::size_t(y - y0 + r + oy) * out.width + (x0 + r + ox);
              for (int c = 0; c < 3; ++c) {
                float value[kChunk];
                for (int q = 0; q < n; ++q) value[q] = fit.beta[c][q];
                for (int p = 1; p < kUnknowns; ++p)
                  for (int q = 0; q < n; ++q) value[q] += fit.beta[p * 3 + c][q] * fit.x[p][q];
                float* sum = out.sum[c].data() + o0;
                for (int q = 0; q < n; ++q) sum[q] += wo[q] * value[q];
              }
              float* total = out.sum[3].data() + o0;
              for (int q = 0; q < n; ++q) total[q] += wo[q];
            }
        }
    }
  });

  // The bands' sums added up, in band order (the result does not depend on
  // the thread count).
  const std::size_t n = std::size_t(w) * h;
  std::array<Plane, 4> total;
  for (Plane& p : total) p.assign(n, 0.0f);
  for (const BandSum& band : sums)
    for (int row = 0; row < band.rows; ++row) {
      const int y = band.y0 - r + row;
      if (y < 0 || y >= h) continue;
      for (int c = 0; c < 4; ++c)
        for (int x = 0; x < w; ++x) total[c][s.at(x, y)] += band.sum[c][std::size_t(row) * band.width + x + r];
    }
  Planes out;
  for (int c = 0; c < 3; ++c) {
    out[c].resize(n);
    for (std::size_t i = 0; i < n; ++i) out[c][i] = total[c][i] / total[3][i];
  }
  return out;
}

}  // namespace

std::vector<glm::vec3> regressionDenoise(const DenoiseInput& in, const DenoiseSettings& settings) {
  const Setup s = setupOf(in, settings);
  const std::size_t n = std::size_t(s.w) * s.h;
  // Candidates per pixel: the unfiltered mean and each strength; each with
  // its estimated squared error (colour units, summed over RGB).
  std::vector<Planes> results;
  std::vector<Plane> errors;
  {
    Planes raw;
    Plane error(n, 0.0f);
    for (int c = 0; c < 3; ++c) {
      raw[c].resize(n);
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t p = s.padded(int(i % s.w), int(i / s.w));
        const float a = s.share[i], m2 = s.modulation[i][c] * s.modulation[i][c];
        raw[c][i] = a * s.half[0][c][p] + (1.0f - a) * s.half[1][c][p];
        error[i] += kRawPenalty * m2 * (a * a * s.halfVar[0][c][i] + (1.0f - a) * (1.0f - a) * s.halfVar[1][c][i]);
      }
    }
    results.push_back(std::move(raw));
    errors.push_back(pf::boxMean(error, s.w, s.h, kErrorRadius));
  }
  for (const float k : kStrengths) {
    // Cross-filtered: each half with weights from the other.
    const Planes first = regress(s, s.half[0], s.half[1], s.guideVar[1], k);
    const Planes second = regress(s, s.half[1], s.half[0], s.guideVar[0], k);
    Planes combined;
    Plane error(n, 0.0f);
    for (int c = 0; c < 3; ++c) {
      combined[c].resize(n);
      for (std::size_t i = 0; i < n; ++i) {
        const float m2 = s.modulation[i][c] * s.modulation[i][c];
        combined[c][i] = s.share[i] * first[c][i] + (1.0f - s.share[i]) * second[c][i];
        // Each filtered half against the other, unfiltered half: an
        // estimate of its error once that half's own variance is taken off.
        const std::size_t p = s.padded(int(i % s.w), int(i / s.w));
        const float ea = (first[c][i] - s.half[1][c][p]) * (first[c][i] - s.half[1][c][p]) - s.halfVar[1][c][i];
        const float eb = (second[c][i] - s.half[0][c][p]) * (second[c][i] - s.half[0][c][p]) - s.halfVar[0][c][i];
        error[i] += m2 * 0.5f * (ea + eb);
      }
    }
    results.push_back(std::move(combined));
    errors.push_back(pf::boxMean(error, s.w, s.h, kErrorRadius));
  }
  // Each pixel takes the candidate of least estimated error; the choice is
  // softened over 3x3 pixels so neighbours that chose differently blend.
  const std::size_t candidates = results.size();
  std::vector<Plane> picks(candidates, Plane(n, 0.0f));
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t best = 0;
    for (std::size_t k = 1; k < candidates; ++k)
      if (errors[k][i] < errors[best][i]) best = k;
    picks[best][i] = 1.0f;
  }
  for (Plane& pick : picks) pick = pf::boxMean(pick, s.w, s.h, 1);
  std::vector<glm::vec3> out(n, glm::vec3(0.0f));
  for (std::size_t k = 0; k < candidates; ++k)
    for (std::size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) out[i][c] += picks[k][i] * results[k][c][i] * s.modulation[i][c];
  return out;
}

}  // namespace tsr::embree::detail
