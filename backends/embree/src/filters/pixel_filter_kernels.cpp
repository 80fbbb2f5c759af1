// The three edge-preserving filters of pixel filtering. Every weight is
// a_i = g_s(spatial) g_c(|c_j - c_i|) g_d(|d_j - d_i|), evaluated as one
// exp of a summed exponent (the range planes are pre-scaled, see Range).
// Sums accumulate w * (x_i - x_j) around the centre value x_j, so a constant
// image comes out bit-exact and large offsets lose no precision.
#include "filters/pixel_filter_detail.hpp"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace tsr::embree::pf {

void parallelRows(int threads, int rows, const std::function<void(int, int)>& body) {
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, rows),
                      [&](const tbb::blocked_range<int>& r) { body(r.begin(), r.end()); });
  });
}

float momentReduction(float sx2, float sy2) {
  constexpr float k = 4.0f * std::numbers::pi_v<float>;
  return 1.0f / std::sqrt((1.0f + k * std::max(sx2, 0.0f)) * (1.0f + k * std::max(sy2, 0.0f)));
}

namespace {

// Spatial exponents -k^2 / (2 sigma^2) for |k| <= radius (3 sigma, at most
// `limit`), stored at table[radius + k]. Rebuilt only when sigma changes,
// so with a fixed sigma each worker computes it once.
struct SpatialTable {
  float sigma = -1.0f;
  int radius = 0;
  std::vector<float> table;

  const float* centre(float s, int limit) {
    if (s != sigma) {
      sigma = s;
      radius = std::clamp(static_cast<int>(std::floor(3.0f * s)), 0, limit);
      table.assign(2 * radius + 1, 0.0f);
      const float k = radius > 0 ? 1.0f / (2.0f * s * s) : 0.0f;
      for (int i = -radius; i <= radius; ++i) table[radius + i] = -static_cast<float>(i * i) * k;
    }
    return table.data() + radius;
  }
};

void transpose(const Plane& in, int w, int h, Plane& out, int threads) {
  out.resize(in.size());
  constexpr int B = 32;
  parallelRows(threads, (h + B - 1) / B, [&](int b0, int b1) {
    for (int by = b0 * B; by < std::min(b1 * B, h); by += B)
      for (int bx = 0; bx < w; bx += B)
        for (int y = by; y < std::min(by + B, h); ++y)
          for (int x = bx; x < std::min(bx + B, w); ++x) out[std::size_t(x) * h + y] = in[std::size_t(y) * w + x];
  });
}

void transpose(const Range& in, int w, int h, Range& out, int threads) {
  transpose(in.r, w, h, out.r, threads);
  transpose(in.g, w, h, out.g, threads);
  transpose(in.b, w, h, out.b, threads);
  transpose(in.d, w, h, out.d, threads);
  transpose(in.e, w, h, out.e, threads);
}

void transpose(const State& in, int w, int h, State& out, int threads) {
  for (auto m :
       {&State::lr, &State::lg, &State::lb, &State::v, &State::mx, &State::vx, &State::my, &State::vy, &State::q})
    transpose(in.*m, w, h, out.*m, threads);
}

void resize(State& s, std::size_t n) {
  for (auto m :
       {&State::lr, &State::lg, &State::lb, &State::v, &State::mx, &State::vx, &State::my, &State::vy, &State::q})
    (s.*m).resize(n);
}

// ---------------------------------------------------------------- bilateral

}  // namespace

void bilateral(const Image& im, const Range& rg, const Plane& sigma, State& s, Plane& r, const KernelParams& p) {
  const int w = im.w, h = im.h;
  const std::size_t n = std::size_t(w) * h;
  State out;
  resize(out, n);
  r.assign(n, 1.0f);
  parallelRows(p.threads, h, [&](int y0, int y1) {
    SpatialTable table;
    for (int y = y0; y < y1; ++y) {
      for (int x = 0; x < w; ++x) {
        const std::size_t j = std::size_t(y) * w + x;
        const float sg = sigma[j];
        const float* sp = table.centre(sg, std::max(w, h));
        const int R = table.radius;
        const float cr = rg.r[j], cg = rg.g[j], cb = rg.b[j], cd = rg.d[j], ce = rg.e[j];
        const float lr = s.lr[j], lg = s.lg[j], lb = s.lb[j], lv = s.v[j];
        const float disc = 9.0f * sg * sg;
        float a = 0, a2 = 0, sr = 0, sgn = 0, sb = 0, sv = 0;
        for (int dy = std::max(-R, -y); dy <= std::min(R, h - 1 - y); ++dy) {
          // Truncate on the disc |p - p_j| <= 3 sigma.
          const int rx = std::min(R, static_cast<int>(std::floor(std::sqrt(std::max(0.0f, disc - float(dy * dy))))));
          const float spy = sp[dy];
          const std::size_t row = std::size_t(y + dy) * w;
          const float* RR = rg.r.data() + row;
          const float* RG = rg.g.data() + row;
          const float* RB = rg.b.data() + row;
          const float* RD = rg.d.data() + row;
          const float* RE = rg.e.data() + row;
          const float* LR = s.lr.data() + row;
          const float* LG = s.lg.data() + row;
          const float* LB = s.lb.data() + row;
          const float* LV = s.v.data() + row;
          const int x0 = std::max(x - rx, 0), x1 = std::min(x + rx, w - 1);
          for (int i = x0; i <= x1; ++i) {
            const float dr = RR[i] - cr, dg = RG[i] - cg, db = RB[i] - cb, dd = RD[i] - cd, de = RE[i] - ce;
            const float wt = fastExp(spy + sp[i - x] - (dr * dr + dg * dg + db * db + dd * dd + de * de));
            a += wt;
            a2 += wt * wt;
            sr += wt * (LR[i] - lr);
            sgn += wt * (LG[i] - lg);
            sb += wt * (LB[i] - lb);
            sv += wt * (LV[i] - lv);
          }
        }
        // The centre weighs exactly 1, so a >= 1.
        const float inv = 1.0f / a;
        out.lr[j] = lr + sr * inv;
        out.lg[j] = lg + sgn * inv;
        out.lb[j] = lb + sb * inv;
        out.v[j] = lv + sv * inv;
        r[j] = std::min(1.0f, a2 * inv * inv);
      }
    }
  });
  s.lr.swap(out.lr);
  s.lg.swap(out.lg);
  s.lb.swap(out.lb);
  s.v.swap(out.v);
}

// ---------------------------------------------------------------- separable

namespace {

// One window of a 1-D pass: sums of w * (value_i - centre value) and the
// raw moments (about the centre pixel) of the composite kernel.
struct Acc {
  float a = 0, lr = 0, lg = 0, lb = 0, v = 0, m1a = 0, m2a = 0, m1o = 0, m2o = 0, q = 0;
};

// Pointers to one row of the pass input; "a" = the pass axis, "o" = the other.
struct Row {
  const float *cr, *cg, *cb, *cd, *ce, *lr, *lg, *lb, *v, *ma, *va, *mo, *vo, *q;
};

struct Centre {
  float lr, lg, lb, v;
};

// Sums over i in [lo, hi] with range value (cr, cg, cb, cd); x = centre.
Acc window(const Row& rw, int x, int lo, int hi, const float* sp, float cr, float cg, float cb, float cd, float ce,
           const Centre& c) {
  Acc s;
  for (int i = lo; i <= hi; ++i) {
    const int k = i - x;
    const float dr = rw.cr[i] - cr, dg = rw.cg[i] - cg, db = rw.cb[i] - cb, dd = rw.cd[i] - cd, de = rw.ce[i] - ce;
    const float wt = fastExp(sp[k] - (dr * dr + dg * dg + db * db + dd * dd + de * de));
    s.a += wt;
    s.lr += wt * (rw.lr[i] - c.lr);
    s.lg += wt * (rw.lg[i] - c.lg);
    s.lb += wt * (rw.lb[i] - c.lb);
    s.v += wt * (rw.v[i] - c.v);
    const float ma = static_cast<float>(k) + rw.ma[i];
    s.m1a += wt * ma;
    s.m2a += wt * (rw.va[i] + ma * ma);
    s.m1o += wt * rw.mo[i];
    s.m2o += wt * (rw.vo[i] + rw.mo[i] * rw.mo[i]);
    s.q += wt * wt * rw.q[i];
  }
  return s;
}

// Adds coefficient * (normalised window) to `sum`. For q the windows are
// treated as disjoint (the centre window overlaps the side ones; the cross
// terms are dropped, which only lowers q, see the r note in the header).
void addNormalised(Acc& sum, const Acc& s, float coefficient) {
  const float k = coefficient / s.a;
  sum.lr += k * s.lr;
  sum.lg += k * s.lg;
  sum.lb += k * s.lb;
  sum.v += k * s.v;
  sum.m1a += k * s.m1a;
  sum.m2a += k * s.m2a;
  sum.m1o += k * s.m1o;
  sum.m2o += k * s.m2o;
  sum.q += k * k * s.q;
}

struct AntialiasModel {
  bool edge = false;
  float cover = 0;  // a-hat of 3.19: how much of the pixel is the +1 side
  float fit = 0;    // w = g_sigmaC(b) of 3.20
  float p0[3]{}, p2[3]{};
};

// Edge model of 3.6.5 in the pass direction: a 1-D Sobel (neighbour
// columns smoothed 1-2-1 across the pass) gives the end points P0, P2; the
// centre colour is projected onto the segment. Colours are pre-scaled by
// 1/(sqrt(2) sigmaC), so |.|^2 is already the Gaussian's exponent.
AntialiasModel fitEdge(const Range& rg, int w, int h, int x, int y) {
  AntialiasModel m;
  if (x < 1 || x + 1 >= w) return m;
  const int ym = std::max(y - 1, 0), yp = std::min(y + 1, h - 1);
  const Plane* planes[3] = {&rg.r, &rg.g, &rg.b};
  float g[3], d[3], gg = 0, dg = 0;
  for (int c = 0; c < 3; ++c) {
    const Plane& P = *planes[c];
    auto at = [&](int xx, int yy) { return P[std::size_t(yy) * w + xx]; };
    m.p0[c] = 0.25f * (at(x - 1, ym) + 2.0f * at(x - 1, y) + at(x - 1, yp));
    m.p2[c] = 0.25f * (at(x + 1, ym) + 2.0f * at(x + 1, y) + at(x + 1, yp));
    g[c] = m.p2[c] - m.p0[c];
    d[c] = at(x, y) - m.p0[c];
    gg += g[c] * g[c];
    dg += d[c] * g[c];
  }
  // Ends closer than sqrt(2) sigmaC: the centre window already spans both sides.
  if (gg <= 1.0f) return m;
  m.cover = std::clamp(dg / gg, 0.0f, 1.0f);
  float b2 = 0;
  for (int c = 0; c < 3; ++c) {
    const float e = d[c] - m.cover * g[c];
    b2 += e * e;
  }
  m.fit = std::exp(-b2);
  m.edge = m.fit > 1e-3f;
  return m;
}

// One 1-D pass along the rows of `in` (w x h in the current orientation).
// alongX says whether rows run along the image's x axis (else the data is
// transposed and rows run along y); it picks which moment planes are "a".
void pass(int w, int h, const Range& rg, const Plane& sigma, float factor, const State& in, State& out, bool alongX,
          const KernelParams& p) {
  const Plane& ma = alongX ? in.mx : in.my;
  const Plane& va = alongX ? in.vx : in.vy;
  const Plane& mo = alongX ? in.my : in.mx;
  const Plane& vo = alongX ? in.vy : in.vx;
  Plane& oma = alongX ? out.mx : out.my;
  Plane& ova = alongX ? out.vx : out.vy;
  Plane& omo = alongX ? out.my : out.mx;
  Plane& ovo = alongX ? out.vy : out.vx;
  parallelRows(p.threads, h, [&](int y0, int y1) {
    SpatialTable table;
    for (int y = y0; y < y1; ++y) {
      const std::size_t row = std::size_t(y) * w;
      const Row rw{rg.r.data() + row,  rg.g.data() + row,  rg.b.data() + row,  rg.d.data() + row, rg.e.data() + row,
                   in.lr.data() + row, in.lg.data() + row, in.lb.data() + row, in.v.data() + row, ma.data() + row,
                   va.data() + row,    mo.data() + row,    vo.data() + row,    in.q.data() + row};
      for (int x = 0; x < w; ++x) {
        const std::size_t j = row + x;
        const float* sp = table.centre(sigma[j] * factor, w);
        const int R = table.radius;
        const Centre c{in.lr[j], in.lg[j], in.lb[j], in.v[j]};
        const int lo = std::max(x - R, 0), hi = std::min(x + R, w - 1);
        const Acc centre = window(rw, x, lo, hi, sp, rg.r[j], rg.g[j], rg.b[j], rg.d[j], rg.e[j], c);
        Acc sum;
        if (p.antialiasRecovery && R > 0) {
          const AntialiasModel m = fitEdge(rg, w, h, x, y);
          if (m.edge) {
            // Left window: range of the -1 side, gathers only to the left; right likewise.
            const Acc left = window(rw, x, lo, x - 1, sp, m.p0[0], m.p0[1], m.p0[2], rg.d[j - 1], rg.e[j - 1], c);
            const Acc right = window(rw, x, x + 1, hi, sp, m.p2[0], m.p2[1], m.p2[2], rg.d[j + 1], rg.e[j + 1], c);
            if (left.a > 0.0f && right.a > 0.0f) {
              addNormalised(sum, left, m.fit * (1.0f - m.cover));
              addNormalised(sum, right, m.fit * m.cover);
              addNormalised(sum, centre, 1.0f - m.fit);
            } else {
              addNormalised(sum, centre, 1.0f);
            }
          } else {
            addNormalised(sum, centre, 1.0f);
          }
        } else {
          addNormalised(sum, centre, 1.0f);
        }
        out.lr[j] = c.lr + sum.lr;
        out.lg[j] = c.lg + sum.lg;
        out.lb[j] = c.lb + sum.lb;
        out.v[j] = c.v + sum.v;
        oma[j] = sum.m1a;
        ova[j] = std::max(0.0f, sum.m2a - sum.m1a * sum.m1a);
        omo[j] = sum.m1o;
        ovo[j] = std::max(0.0f, sum.m2o - sum.m1o * sum.m1o);
        out.q[j] = std::min(1.0f, sum.q);
      }
    }
  });
}

}  // namespace

void separable(const Image& im, const Range& rg, const Plane& sigma, State& s, Plane& r, const KernelParams& p) {
  const int w = im.w, h = im.h;
  const unsigned N = std::max(1u, p.iterations);
  Range rt;
  Plane sigmaT;
  transpose(rg, w, h, rt, p.threads);
  transpose(sigma, w, h, sigmaT, p.threads);
  State tmp;
  resize(tmp, s.lr.size());
  // 3.14: sigma_k = sigma sqrt(3) 2^(N-k) / sqrt(4^N - 1); the squares sum to sigma^2.
  const float norm = std::sqrt(3.0f / (std::pow(4.0f, float(N)) - 1.0f));
  for (unsigned k = 1; k <= N; ++k) {
    const float factor = norm * std::pow(2.0f, float(N - k));
    pass(w, h, rg, sigma, factor, s, tmp, true, p);
    transpose(tmp, w, h, s, p.threads);
    pass(h, w, rt, sigmaT, factor, s, tmp, false, p);
    transpose(tmp, h, w, s, p.threads);
  }
  r.resize(s.lr.size());
  for (std::size_t i = 0; i < r.size(); ++i) r[i] = std::max(s.q[i], momentReduction(s.vx[i], s.vy[i]));
}

// ---------------------------------------------------------------- a-trous

namespace {

// A per-pixel, per-level rotation of the 5x5 tap pattern, and a sub-pixel
// shift of it. With the same axis-aligned pattern everywhere, every bright
// sample is copied onto the lattice of each level's step, and the image
// prints that lattice (a grid over flat walls). Rotated by an angle drawn
// from the pixel and the level, the copies land on no common lattice; the
// kernel's spatial variance (the sum of the taps' squared offsets) is the
// same at every angle. Tap positions fall between pixels; rounded, a step
// of 1.75 would read only even offsets near 0 degrees (a pattern of
// period 2), so they are rounded stochastically: down or up with the
// probability of the fraction, by the shift drawn with the angle.
struct Rotation {
  float c, s;
};

struct TapPattern {
  Rotation rotation;
  float shiftX, shiftY;  // in [0, 1): floor(position + shift) rounds stochastically
};

// 64 angles over [0, pi/2), the square pattern's symmetry: a table, as a
// sine and cosine per pixel and level would cost as much as the taps.
constexpr int kAngles = 64;

const std::array<Rotation, kAngles>& rotations() {
  static const std::array<Rotation, kAngles> table = [] {
    std::array<Rotation, kAngles> t{};
    for (int i = 0; i < kAngles; ++i) {
      const double angle = 0.5 * std::numbers::pi * (i + 0.5) / kAngles;
      t[i] = {float(std::cos(angle)), float(std::sin(angle))};
    }
    return t;
  }();
  return table;
}

TapPattern tapPattern(int x, int y, unsigned level) {
  std::uint64_t h = (std::uint64_t(std::uint32_t(x)) << 32 | std::uint32_t(y)) ^ (std::uint64_t(level) << 58);
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdull;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ull;
  h ^= h >> 33;
  constexpr float kUnit = 1.0f / 65536.0f;
  return {rotations()[h >> 58], float((h >> 16) & 0xFFFF) * kUnit, float(h & 0xFFFF) * kUnit};
}

}  // namespace

void atrous(const Image& im, const Range& rg, const Plane& sigma, State& s, Plane& r, const KernelParams& p) {
  const int w = im.w, h = im.h;
  const unsigned N = std::max(1u, p.iterations);
  constexpr float B3[5] = {1.0f / 16, 1.0f / 4, 3.0f / 8, 1.0f / 4, 1.0f / 16};  // variance 1 tap^2
  // Hole spacing h_k = sigma sqrt(3) 2^(k-1) / sqrt(4^N - 1): the levels'
  // variances sum to sigma^2, so sigmaS means the same as for the other kernels.
  const float norm = std::sqrt(3.0f / (std::pow(4.0f, float(N)) - 1.0f));
  State tmp;
  resize(tmp, s.lr.size());
  for (unsigned k = 1; k <= N; ++k) {
    const float factor = norm * std::pow(2.0f, float(k - 1));
    parallelRows(p.threads, h, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y) {
        for (int x = 0; x < w; ++x) {
          const std::size_t j = std::size_t(y) * w + x;
          const float step = std::min(sigma[j] * factor, float(std::max(w, h)));
          const TapPattern pattern = tapPattern(x, y, k);
          const Rotation rot = pattern.rotation;
          const float cr = rg.r[j], cg = rg.g[j], cb = rg.b[j], cd = rg.d[j], ce = rg.e[j];
          const float lr = s.lr[j], lg = s.lg[j], lb = s.lb[j], lv = s.v[j];
          float a = 0, sr = 0, sgn = 0, sb = 0, sv = 0, m1x = 0, m2x = 0, m1y = 0, m2y = 0, q = 0;
          for (int ty = 0; ty < 5; ++ty) {
            for (int tx = 0; tx < 5; ++tx) {
              const float u = float(tx - 2) * step, v = float(ty - 2) * step;
              // The centre tap stays on the pixel itself.
              const int ox =
                  tx == 2 && ty == 2 ? 0 : static_cast<int>(std::floor(rot.c * u - rot.s * v + pattern.shiftX));
              const int oy =
                  tx == 2 && ty == 2 ? 0 : static_cast<int>(std::floor(rot.s * u + rot.c * v + pattern.shiftY));
              const int xx = x + ox, yy = y + oy;
              if (xx < 0 || xx >= w || yy < 0 || yy >= h) continue;
              const std::size_t i = std::size_t(yy) * w + xx;
              const float dr = rg.r[i] - cr, dg = rg.g[i] - cg, db = rg.b[i] - cb, dd = rg.d[i] - cd, de = rg.e[i] - ce;
              const float wt = B3[ty] * B3[tx] * fastExp(-(dr * dr + dg * dg + db * db + dd * dd + de * de));
              a += wt;
              sr += wt * (s.lr[i] - lr);
              sgn += wt * (s.lg[i] - lg);
              sb += wt * (s.lb[i] - lb);
              sv += wt * (s.v[i] - lv);
              const float mx = float(ox) + s.mx[i], my = float(oy) + s.my[i];
              m1x += wt * mx;
              m2x += wt * (s.vx[i] + mx * mx);
              m1y += wt * my;
              m2y += wt * (s.vy[i] + my * my);
              q += wt * wt * s.q[i];
            }
          }
          const float inv = 1.0f / a;  // the centre tap alone gives a >= 9/64
          tmp.lr[j] = lr + sr * inv;
          tmp.lg[j] = lg + sgn * inv;
          tmp.lb[j] = lb + sb * inv;
          tmp.v[j] = lv + sv * inv;
          tmp.mx[j] = m1x * inv;
          tmp.vx[j] = std::max(0.0f, m2x * inv - tmp.mx[j] * tmp.mx[j]);
          tmp.my[j] = m1y * inv;
          tmp.vy[j] = std::max(0.0f, m2y * inv - tmp.my[j] * tmp.my[j]);
          tmp.q[j] = std::min(1.0f, q * inv * inv);
        }
      }
    });
    std::swap(s, tmp);
  }
  r.resize(s.lr.size());
  for (std::size_t i = 0; i < r.size(); ++i) r[i] = std::max(s.q[i], momentReduction(s.vx[i], s.vy[i]));
}

}  // namespace tsr::embree::pf
