// The filtering step of radiance filtering (Schwenk 2013, 4.3): adapts
// each pixel's kernel radius to its variance, projects the kernel into the
// tangent plane of the pixel's radiance sample and reflects the neighbours'
// incident radiance with the pixel's own BSDF (eqs. 4.8-4.12).
#include "filters/radiance_filter_step.hpp"

#include "tracing/bsdf.hpp"
#include "tsr/embree/error.hpp"
#include "tsr/embree/framebuffer.hpp"
#include "tsr/embree/sampling.hpp"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace tsr::embree {

void RadianceFilterSettings::validate() const {
  auto finiteNonNegative = [](float v) { return std::isfinite(v) && v >= 0.0f; };
  if (!(std::isfinite(threshold) && threshold > 0.0f)) throw Error("radiance filter threshold must be > 0");
  if (!finiteNonNegative(warmupRadius)) throw Error("radiance filter warmupRadius must be >= 0 pixels");
  if (warmupFrames == 0) throw Error("radiance filter warmupFrames must be at least 1");
  if (!finiteNonNegative(maxRadius)) throw Error("radiance filter maxRadius must be >= 0 pixels");
  if (!(std::isfinite(blend) && blend >= 0.0f && blend < 1.0f)) throw Error("radiance filter blend must be in [0, 1)");
}

namespace {
// Added to the squared background of the hand-over's perceived variance.
// Weber's law fails in the dark (de Vries-Rose): below a background of
// about 0.1 noise is judged in absolute terms, so dark pixels do not keep
// the filtered estimate, and its bias, long after the rest let go.
constexpr float kBlendBackgroundFloor = 0.01f;
// Added to the squared background radiance of the perceived variance, so
// that black pixels do not ask for infinite kernels.
constexpr float kBackgroundFloor = 1e-4f;
}  // namespace

RadianceAccumulator::RadianceAccumulator(std::uint32_t width, std::uint32_t height) : width_(width), height_(height) {
  if (width == 0 || height == 0) throw Error("radiance accumulator size must be non-zero");
  reset();
}

void RadianceAccumulator::reset() {
  pixels_.assign(std::size_t(width_) * height_, Pixel{});
  samples_.assign(std::size_t(width_) * height_, RadianceSample{});
  epoch_ = 0;
}

glm::vec3 RadianceAccumulator::radiance(const FrameBuffer& fb, std::uint32_t x, std::uint32_t y) const {
  const Pixel& p = pixels_[at(x, y)];
  const glm::vec3 direct = fb.mean(Channel::Direct, x, y), caustic = fb.mean(Channel::Caustic, x, y);
  // The accumulated filtered estimate keeps the bias of its early, wide
  // kernels (it fades only as 1/frames), so the unfiltered mean of the
  // same paths takes over as its perceived variance u falls from twice
  // the threshold to the threshold: the filtered estimate was built to
  // meet t, so it is kept while the unfiltered one is far noisier, and the
  // image converges to the path tracer's. u is the kernel-smoothed variance
  // of the filtering step, not the pixel's own: where light arrives only
  // by rare indirect paths, most pixels' few samples are all zero, their
  // own variance 0, and they would show their unfiltered black.
  const glm::vec3 unfiltered = fb.mean(Channel::Indirect, x, y) - caustic;
  const std::uint32_t n = fb.sampleCount(x, y);
  float s = 0.0f;
  if (n > 1 && threshold_ > 0.0f) {
    const float lb = luminance(direct + p.indirect + caustic);
    const float u = p.variance * (lb * lb + kBackgroundFloor) / (lb * lb + kBlendBackgroundFloor) / float(n);
    s = std::clamp(2.0f - u / threshold_, 0.0f, 1.0f);
  }
  return direct + caustic + s * unfiltered + (1.0f - s) * p.indirect;
}

std::vector<glm::vec3> RadianceAccumulator::radianceImage(const FrameBuffer& fb) const {
  std::vector<glm::vec3> out(pixels_.size());
  for (std::uint32_t y = 0; y < height_; ++y)
    for (std::uint32_t x = 0; x < width_; ++x) out[at(x, y)] = radiance(fb, x, y);
  return out;
}

namespace {

// Kernel radius (pixels) with which the variance and irradiance estimates are
// still smoothed once the radiance is no longer filtered.
constexpr float kVarianceRadius = 2.0f;
// Half thickness of the kernel's prism along the normal, relative to its
// radius (4.18): tolerates curvature, rejects surfaces behind a step.
constexpr float kThickness = 0.25f;
// Least cosine of incidence in the kernel's elongation (4.21).
constexpr float kMinCosine = 0.2f;
// Relative standard deviation of the bilateral range kernel (4.27).
constexpr float kRangeSigma = 0.1f;
// Effective sample count of an Epanechnikov kernel of radius r over one
// sample per pixel: (sum w)^2 / sum w^2 = 0.75 pi r^2.
constexpr float kEpanechnikovArea = 0.75f * kPi;

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// What a neighbour contributes, packed into one cache line.
struct Neighbour {
  glm::vec3 position;
  float variance;  // perceived variance of one sample of its pixel
  glm::vec3 normal;
  float range;  // luminance of its accumulated filtered irradiance
  glm::vec3 wi;
  float valid;
  glm::vec3 radiance;  // Ľ_i, zero where the path ended at the vertex
  float irradiance;    // luminance of this frame's one-sample irradiance estimate
};

// GGX alpha to the exponent of the Blinn distribution with the same
// curvature at the peak: D_blinn ~ (e + 2) cos^e, D_ggx ~ 1 / alpha^2 near
// the normal, so e ~ 2 / alpha^2 - 2. Lambert and the smoothest GGX
// surfaces fall to the ends; the exponent is at least 1 so that samples on
// surfaces facing away (the other side of a corner) never count.
float blinnExponent(const RadianceSample& s) {
  if (closestClass(s.type, std::sqrt(s.alpha), s.metallic, s.transmission) == MaterialType::Diffuse) return 1.0f;
  return std::clamp(2.0f / (s.alpha * s.alpha) - 2.0f, 1.0f, 1e6f);
}

// Eq. 3.12/3.13 with Cov = 0: the largest share s of the unfiltered
// estimate (variance u) blended with the filtered one (variance f) that
// keeps s^2 u + (1-s)^2 f <= t.
float blendFactor(float u, float f, float t) {
  if (u <= t) return 1.0f;
  float disc = t * u + t * f - u * f;
  if (disc < 0.0f || u + f <= 0.0f) return 0.0f;
  return std::clamp((f + std::sqrt(disc)) / (u + f), 0.0f, 1.0f);
}

// Phase 1 for one pixel: what its neighbours read of it, from the previous
// frame's state (`indirect` and `range` are its accumulated indirect light
// and filtered irradiance).
Neighbour neighbourOf(const FrameBuffer& fb, std::uint32_t x, std::uint32_t y, const RadianceSample& s,
                      glm::vec3 indirect, float range) {
  Neighbour n;
  const float background = luminance(fb.mean(Channel::Direct, x, y) + indirect);
  const float v = luminance(fb.variance(Channel::Indirect, x, y)) / (background * background + kBackgroundFloor);
  n.position = s.position;
  n.normal = s.normal;
  n.wi = s.wi;
  n.valid = s.valid ? 1.0f : 0.0f;
  n.variance = std::isfinite(v) ? v : 0.0f;
  n.range = range;
  const bool sampled = s.valid && s.pdf > 0.0f;
  n.radiance = sampled ? s.radiance : glm::vec3(0.0f);
  n.irradiance = sampled ? luminance(s.radiance) * std::abs(glm::dot(s.wi, s.normal)) / s.pdf : 0.0f;
  if (!std::isfinite(n.irradiance)) n.irradiance = 0.0f;
  return n;
}

// Step 3: the kernel radius (4.1, 4.2, 4.14, 4.15) of a pixel in its k-th
// frame, from its estimated variance and occlusion.
float kernelRadius(const RadianceFilterSettings& cfg, std::uint32_t k, float variance, float occlusion) {
  const float target = float(2 * k - 1) * cfg.threshold * (1.0f - cfg.blend);
  // After the warm-up the variance sets the radius, but never below
  // the warm-up's own schedule r_w1/sqrt(k): where every neighbour
  // so far missed the rare bright paths, the estimated variance is
  // zero and a radius from it would leave the pixel unfiltered and
  // black. The floor still shrinks to nothing as k grows.
  const float schedule = cfg.warmupRadius / std::sqrt(float(k));
  float r = k <= cfg.warmupFrames ? schedule : std::max(schedule, std::sqrt(variance / target / kEpanechnikovArea));
  // Occlusion narrows the kernel in corners (4.3.1), but only by
  // half: where light arrives only by rare indirect paths, a
  // kernel shrunk below a pixel leaves the corner its own
  // unfiltered, mostly black, samples.
  if (cfg.ambientOcclusion) r *= 0.5f + 0.5f * occlusion;
  r = std::min(r, cfg.maxRadius);
  if (!std::isfinite(r)) r = 0.0f;
  return r;
}

// Step 4: the kernel of `radius` pixels projected into the tangent plane
// of the pixel's sample (4.19-4.22), with the pixel's BSDF prepared at its
// wo (every neighbour is evaluated at it) and the range term's scale.
struct Kernel {
  glm::vec3 n;
  Frame frame;
  glm::vec3 aS, aD;
  float invS, invD, delta, occlusionReach;
  Bsdf bsdf;
  glm::vec3 woL;
  bool diffuse;  // f cos / pdf is the albedo
  float e;       // the Blinn exponent of the normal term
  float rangeX, rangeScale;

  Kernel(const RadianceSample& own, float radius, float range)
      : n(own.normal), frame(n), e(blinnExponent(own)), rangeX(range) {
    const glm::vec3 d = -own.wo;
    const float footprint = std::max(own.distance * own.pixelAngle, 1e-8f);
    const float rS = radius * footprint;
    const float cosI = std::max(kMinCosine, std::abs(glm::dot(d, n)));
    const float rD = rS / cosI;
    delta = kThickness * rS;
    aD = d - glm::dot(d, n) * n;
    aD = glm::dot(aD, aD) > 1e-12f ? glm::normalize(aD) : frame.t;
    aS = glm::cross(aD, n);
    invS = 1.0f / rS;
    invD = 1.0f / rD;
    occlusionReach = 2.0f * rD;

    bsdf.type = own.type;
    bsdf.colour = own.colour;
    bsdf.alpha = own.alpha;
    bsdf.eta = own.eta;
    bsdf.metallic = own.metallic;
    bsdf.specular = own.specular;
    bsdf.transmission = own.transmission;
    woL = frame.toLocal(own.wo);
    bsdf.prepare(woL);
    diffuse = own.type == MaterialType::Diffuse;
    rangeScale = -0.5f / std::max(1e-12f, (kRangeSigma * rangeX) * (kRangeSigma * rangeX));
  }
};

// What the neighbours within the kernel add up to.
struct Gathered {
  glm::vec3 sum{0.0f};
  float weights = 0.0f, weights2 = 0.0f;                   // modified kernel (with the range term)
  float plain = 0.0f, variance = 0.0f, irradiance = 0.0f;  // unmodified kernel
  float occluded = 0.0f, neighbours = 0.0f;
};

// The neighbours of pixel (x, y) within `radius`, a fixed sequential loop:
// the result does not depend on the thread count. Only with `filter` do
// they add to the filtered estimate; with `bilateral` weighted by range.
Gathered gather(const std::vector<Neighbour>& nb, std::uint32_t w, std::uint32_t h, std::uint32_t x, std::uint32_t y,
                const RadianceSample& own, const Kernel& kn, float radius, bool filter, bool bilateral) {
  Gathered g;
  const int ri = int(std::floor(radius));
  const float r2 = radius * radius;
  const int ylo = std::max(0, int(y) - ri), yhi = std::min(int(h) - 1, int(y) + ri);
  for (int yy = ylo; yy <= yhi; ++yy) {
    const float dy = float(yy - int(y));
    const int span = int(std::floor(std::sqrt(std::max(0.0f, r2 - dy * dy))));
    const int xlo = std::max(0, int(x) - span), xhi = std::min(int(w) - 1, int(x) + span);
    const Neighbour* row = &nb[std::size_t(yy) * w];
    for (int xx = xlo; xx <= xhi; ++xx) {
      const Neighbour& q = row[xx];
      if (q.valid == 0.0f) continue;
      const glm::vec3 dp = q.position - own.position;
      const float height = glm::dot(dp, kn.n);
      const float dist2 = glm::dot(dp, dp);
      if (dist2 < kn.occlusionReach * kn.occlusionReach) {
        // Screen-space occlusion: the sine of the elevation of
        // neighbours above the tangent plane (those inside the prism
        // count as 0, sparing the square root).
        g.neighbours += 1.0f;
        if (height > kn.delta) g.occluded += height / std::sqrt(dist2);
      }
      if (std::abs(height) > kn.delta) continue;
      const float u = glm::dot(dp, kn.aS) * kn.invS, v = glm::dot(dp, kn.aD) * kn.invD;
      const float rho2 = u * u + v * v;
      if (rho2 >= 1.0f) continue;
      const float c = glm::dot(kn.n, q.normal);
      if (c <= 0.0f) continue;
      const float kernel = (1.0f - rho2) * (kn.e == 1.0f ? c : std::pow(c, kn.e));
      if (!(kernel > 0.0f)) continue;
      g.plain += kernel;
      g.variance += kernel * q.variance;
      g.irradiance += kernel * q.irradiance;
      if (!filter) continue;
      float wgt = kernel;
      if (bilateral) {
        const float diff = q.range - kn.rangeX;
        wgt *= std::exp(diff * diff * kn.rangeScale);
      }
      g.weights += wgt;
      g.weights2 += wgt * wgt;
      if (q.radiance.x == 0.0f && q.radiance.y == 0.0f && q.radiance.z == 0.0f) continue;
      // Eq. 4.8: the neighbour's incident radiance, reflected by this
      // pixel's BSDF and divided by this pixel's pdf (MIS approximation 4.7).
      const glm::vec3 wiL = kn.frame.toLocal(q.wi);
      if (kn.diffuse) {
        if (wiL.z > 0.0f) g.sum += wgt * q.radiance;  // f cos / pdf = albedo
      } else {
        float pdf;
        const glm::vec3 f = kn.bsdf.evalPdf(kn.woL, wiL, &pdf);
        if (pdf > 0.0f) g.sum += (wgt / pdf) * f * q.radiance;
      }
    }
  }
  if (kn.diffuse) g.sum *= own.colour;
  return g;
}

// Phase 2 for pixel (x, y): filtered where its radius allows and no mask
// holds it back, then accumulated into its running mean. `Pixel` is the
// accumulator's (private) pixel state.
template <class Pixel>
void filterPixel(const FrameBuffer& fb, const RadianceFilterSettings& cfg, const std::vector<Neighbour>& nb,
                 std::uint32_t w, std::uint32_t h, std::uint32_t x, std::uint32_t y,
                 const std::vector<RadianceSample>& samples, std::vector<Pixel>& pixels) {
  const std::size_t i = std::size_t(y) * w + x;
  const RadianceSample& own = samples[i];
  Pixel& px = pixels[i];
  const std::uint32_t k = px.frames + 1;
  px.mask |= own.mask;
  glm::vec3 estimate = own.unfiltered;
  const bool masked = cfg.hybrid && (px.mask & kMaskReflectRefract);
  px.radius = 0.0f;
  if (own.valid) {
    const float r = kernelRadius(cfg, k, px.variance, px.occlusion);
    const bool filter = r >= 1.0f && !masked;
    const float radius = filter ? r : std::min(kVarianceRadius, cfg.maxRadius);
    const Kernel kn(own, radius, nb[i].range);
    const bool bilateral = cfg.bilateral && filter && k > kBilateralStart;
    const Gathered g = gather(nb, w, h, x, y, own, kn, radius, filter, bilateral);
    if (g.plain > 0.0f) {
      px.variance = g.variance / g.plain;
      px.irradiance += (g.irradiance / g.plain - px.irradiance) / float(k);
    }
    if (g.neighbours > 0.0f) px.occlusion = std::clamp(1.0f - g.occluded / g.neighbours, 0.0f, 1.0f);
    if (filter && g.weights > 0.0f) {
      const glm::vec3 filtered = own.throughput * g.sum / g.weights;
      if (finite(filtered)) {
        px.radius = r;
        estimate = filtered;
        if (cfg.blend > 0.0f) {
          // 4.6.3: fill the share of T_k left over with the unfiltered sample.
          const float u = px.variance;
          const float f = px.variance * g.weights2 / (g.weights * g.weights);
          const float s = blendFactor(u, f, float(2 * k - 1) * cfg.threshold);
          estimate = s * own.unfiltered + (1.0f - s) * filtered;
        }
      }
    }
  }
  px.frames = k;
  // A pixel left to pixel filtering holds the unfiltered mean of all its
  // paths, also of frames filtered before the mask showed up.
  if (masked)
    px.indirect = fb.mean(Channel::Indirect, x, y) - fb.mean(Channel::Caustic, x, y);
  else
    px.indirect += (estimate - px.indirect) / float(k);
}

}  // namespace

// Phase 1 gathers what neighbours read; phase 2 filters each pixel in
// place: its radius, the kernel, the neighbours within it, and the
// estimate blended and accumulated.
void RadianceFilterStep::run(const FrameBuffer& fb, RadianceAccumulator& acc, const RadianceFilterSettings& cfg) {
  acc.threshold_ = cfg.threshold;
  if (acc.epoch_ != fb.epoch()) {
    acc.pixels_.assign(acc.pixels_.size(), RadianceAccumulator::Pixel{});
    acc.epoch_ = fb.epoch();
  }
  const std::uint32_t w = acc.width_, h = acc.height_;
  const std::vector<RadianceSample>& samples = acc.samples_;
  std::vector<RadianceAccumulator::Pixel>& pixels = acc.pixels_;

  // Phase 1: what neighbours read, from the previous frame's state, so that
  // phase 2 may update pixels in place in any order.
  std::vector<Neighbour> nb(samples.size());
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, h), [&](const tbb::blocked_range<std::uint32_t>& rows) {
    for (std::uint32_t y = rows.begin(); y != rows.end(); ++y)
      for (std::uint32_t x = 0; x < w; ++x) {
        const std::size_t i = std::size_t(y) * w + x;
        nb[i] = neighbourOf(fb, x, y, samples[i], pixels[i].indirect, pixels[i].irradiance);
      }
  });

  // Phase 2: one pixel's estimate from its neighbours.
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, h), [&](const tbb::blocked_range<std::uint32_t>& rows) {
    for (std::uint32_t y = rows.begin(); y != rows.end(); ++y)
      for (std::uint32_t x = 0; x < w; ++x) filterPixel(fb, cfg, nb, w, h, x, y, samples, pixels);
  });
}

}  // namespace tsr::embree
