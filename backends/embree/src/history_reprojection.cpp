// FrameBuffer::reproject: a view change keeps what the samples knew.
#include "tsr/embree/framebuffer.hpp"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>
#include <type_traits>

namespace tsr::embree {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
// How far the depth of an old pixel may lie from where the surface is
// predicted: the same bound the first new sample is held to.
constexpr float kGatherDepthTolerance = 0.05f;
// Bilinear weight below which a pixel takes nothing from the history.
constexpr float kLeastWeight = 1e-3f;

// One camera's mapping between camera space and continuous pixel
// coordinates of a region (pixel (i, j) spans [i, i + 1) x [j, j + 1)).
struct Projection {
  Projection(const Camera& c, const Region& r)
      : toWorld(c.cameraToWorld),
        toCamera(glm::inverse(c.cameraToWorld)),
        left(c.left),
        right(c.right),
        bottom(c.bottom),
        top(c.top),
        near(c.near),
        width(float(r.width)),
        height(float(r.height)),
        x0(float(r.x0)),
        y0(float(r.y0)),
        columns(r.regionWidth()),
        rows(r.regionHeight()) {}

  // The window point (on the near plane) at pixel coordinates (fx, fy).
  glm::vec3 windowPoint(float fx, float fy) const {
    return {left + (right - left) * ((fx + x0) / width), top - (top - bottom) * ((fy + y0) / height), -near};
  }
  // Where camera-space q (in front: q.z < 0) lands, in pixel coordinates.
  glm::vec2 pixelOf(const glm::vec3& q) const {
    const float s = near / -q.z;
    return {(q.x * s - left) / (right - left) * width - x0, (top - q.y * s) / (top - bottom) * height - y0};
  }
  // The world point a pixel's centre shows at camera-space depth d, or (d
  // infinite) the direction it looks in, as w = 0.
  glm::vec4 worldAt(std::uint32_t x, std::uint32_t y, float d) const {
    const glm::vec3 w = windowPoint(float(x) + 0.5f, float(y) + 0.5f);
    return std::isfinite(d) ? toWorld * glm::vec4(w * (d / near), 1.0f) : toWorld * glm::vec4(w, 0.0f);
  }
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < int(columns) && y < int(rows); }
  // Pixel coordinates within a pixel of the region (and so safe to turn
  // into ints): a point near the eye plane projects arbitrarily far, or to
  // infinity or NaN.
  bool nearRegion(const glm::vec2& at) const {
    return at.x >= -1.0f && at.y >= -1.0f && at.x <= float(columns) + 1.0f && at.y <= float(rows) + 1.0f;
  }

  glm::mat4 toWorld, toCamera;
  float left, right, bottom, top, near;
  float width, height, x0, y0;
  std::uint32_t columns, rows;
};

// Each instance's motion from then to now (world to world), and back.
struct InstanceMotions {
  InstanceMotions(std::span<const glm::mat4> then, std::span<const glm::mat4> now) {
    const std::size_t n = std::min(then.size(), now.size());
    forward.resize(n);
    backward.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      if (then[i] == now[i]) {
        forward[i] = backward[i] = glm::mat4(1.0f);
        continue;
      }
      forward[i] = now[i] * glm::inverse(then[i]);
      backward[i] = glm::inverse(forward[i]);
    }
  }
  bool known(std::uint32_t object) const { return object < forward.size(); }
  std::vector<glm::mat4> forward, backward;
};

// What the new view is predicted to show per pixel, from the old depths.
struct Prediction {
  std::vector<float> depth;  // new camera-space depth; infinity: nothing predicted, or the sky
  std::vector<std::uint32_t> object;
  std::vector<std::uint8_t> sky;
};

// 1. Splat: every old pixel's nearest hit, moved with its instance, lands
// in the new view; the nearest landing per pixel is the prediction. Rows
// splat in parallel: a landing is kept by an atomic minimum of (depth,
// instance) packed in 64 bits (positive floats order as their bits), so
// the result does not depend on the order (equal depths: the lower id).
template <class Pixel>
Prediction splatNearest(const std::vector<Pixel>& old, const Projection& from, const Projection& to,
                        const InstanceMotions& motions) {
  const std::size_t size = std::size_t(to.columns) * to.rows;
  constexpr std::uint64_t kNothing = ~std::uint64_t{0};
  std::vector<std::uint64_t> nearest(size, kNothing);
  std::vector<std::uint8_t> skyLanded(size, 0);
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, from.rows),
                    [&](const tbb::blocked_range<std::uint32_t>& rows) {
                      for (std::uint32_t oy = rows.begin(); oy != rows.end(); ++oy)
                        for (std::uint32_t ox = 0; ox < from.columns; ++ox) {
                          const Pixel& p = old[std::size_t(oy) * from.columns + ox];
                          if (p.count == 0) continue;
                          const bool hit = std::isfinite(p.depth);
                          if (hit && !motions.known(p.object)) continue;
                          glm::vec4 world = from.worldAt(ox, oy, p.depth);
                          if (hit) world = motions.forward[p.object] * world;
                          const glm::vec3 q(to.toCamera * world);
                          if (!(q.z < 0.0f)) continue;
                          const glm::vec2 at = to.pixelOf(q);
                          if (!to.nearRegion(at)) continue;
                          const int x = int(std::floor(at.x)), y = int(std::floor(at.y));
                          if (!to.inside(x, y)) continue;
                          const std::size_t i = std::size_t(y) * to.columns + std::uint32_t(x);
                          if (!hit) {
                            std::atomic_ref<std::uint8_t>(skyLanded[i]).store(1, std::memory_order_relaxed);
                            continue;
                          }
                          const std::uint64_t key = std::uint64_t(std::bit_cast<std::uint32_t>(-q.z)) << 32 | p.object;
                          std::atomic_ref<std::uint64_t> slot(nearest[i]);
                          std::uint64_t held = slot.load(std::memory_order_relaxed);
                          while (key < held && !slot.compare_exchange_weak(held, key, std::memory_order_relaxed)) {}
                        }
                    });
  Prediction splat{std::vector<float>(size, kInfinity), std::vector<std::uint32_t>(size, kNoObject),
                   std::move(skyLanded)};
  for (std::size_t i = 0; i < size; ++i)
    if (nearest[i] != kNothing) {
      splat.depth[i] = std::bit_cast<float>(std::uint32_t(nearest[i] >> 32));
      splat.object[i] = std::uint32_t(nearest[i]);
    }
  return splat;
}

// 2. Gaps one pixel wide (a surface seen larger than before) take their
// nearest neighbour's prediction; the first sample checks it.
Prediction fillGaps(const Prediction& splat, const Projection& to) {
  Prediction predicted = splat;
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, to.rows), [&](const tbb::blocked_range<std::uint32_t>& rows) {
    for (std::uint32_t y = rows.begin(); y != rows.end(); ++y)
      for (std::uint32_t x = 0; x < to.columns; ++x) {
        const std::size_t i = std::size_t(y) * to.columns + x;
        if (std::isfinite(splat.depth[i]) || splat.sky[i]) continue;
        bool sky = false;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            if (!to.inside(int(x) + dx, int(y) + dy)) continue;
            const std::size_t n = std::size_t(int(y) + dy) * to.columns + std::uint32_t(int(x) + dx);
            sky = sky || splat.sky[n];
            if (splat.depth[n] < predicted.depth[i]) {
              predicted.depth[i] = splat.depth[n];
              predicted.object[i] = splat.object[n];
            }
          }
        if (!std::isfinite(predicted.depth[i])) predicted.sky[i] = sky;
      }
  });
  return predicted;
}

// 3. Gather: the old pixels around where new pixel (x, y)'s predicted surface was, with
// their bilinear weights: those that saw the same instance at that depth,
// or the sky. A silhouette pixel's far side does not count: what it holds
// is mostly the near side's.
template <class Pixel>
struct Taps {
  const Pixel* pixel[4];
  float weight[4];
  float total = 0.0f;
  int n = 0;
};

template <class Pixel>
Taps<Pixel> historyTaps(const std::vector<Pixel>& old, const Projection& from, const Projection& to,
                        const InstanceMotions& motions, const Prediction& predicted, std::uint32_t x, std::uint32_t y) {
  Taps<Pixel> taps;
  const std::size_t i = std::size_t(y) * to.columns + x;
  const float d = predicted.depth[i];
  const bool hit = std::isfinite(d);
  if (!hit && !predicted.sky[i]) return taps;
  const std::uint32_t object = predicted.object[i];
  glm::vec4 world = to.worldAt(x, y, d);
  if (hit) world = motions.backward[object] * world;
  const glm::vec3 q(from.toCamera * world);
  if (!(q.z < 0.0f)) return taps;
  const glm::vec2 at = from.pixelOf(q) - glm::vec2(0.5f);
  if (!from.nearRegion(at)) return taps;
  const int bx = int(std::floor(at.x)), by = int(std::floor(at.y));
  const float tx = at.x - float(bx), ty = at.y - float(by);
  for (int k = 0; k < 4; ++k) {
    const int ox = bx + (k & 1), oy = by + (k >> 1);
    const float w = ((k & 1) ? tx : 1.0f - tx) * ((k >> 1) ? ty : 1.0f - ty);
    if (w <= 0.0f || !from.inside(ox, oy)) continue;
    const Pixel& p = old[std::size_t(oy) * from.columns + std::uint32_t(ox)];
    if (p.count == 0) continue;
    const float dq = -q.z;
    const bool seen =
        hit ? p.object == object && std::abs(p.depth - dq) <= kGatherDepthTolerance * dq : !std::isfinite(p.depth);
    if (!seen) continue;
    taps.pixel[taps.n] = &p;
    taps.weight[taps.n++] = w;
    taps.total += w;
  }
  return taps;
}

// 4. Blend: the taps blended into `out` (an empty pixel), counts capped at
// `limit`, for a surface predicted at depth d (infinite: the sky). The
// halves the denoiser compares (FrameBuffer's first half and prefix) are
// blended like the rest: each of the old pixels' own. False: nothing carried.
template <class Pixel>
bool blendTaps(const Taps<Pixel>& taps, float d, std::uint32_t object, std::uint32_t limit, Pixel& out) {
  constexpr int channels = int(std::extent_v<decltype(Pixel::mean)>);
  const bool hit = std::isfinite(d);
  float count = 0.0f, rangeCount = 0.0f, rangeHits = 0.0f, rangeWeight = 0.0f;
  glm::vec3 variance[channels]{};
  for (int k = 0; k < taps.n; ++k) {
    const Pixel& p = *taps.pixel[k];
    const float w = taps.weight[k] / taps.total;
    count += w * float(p.count);
    for (int c = 0; c < channels; ++c) {
      out.mean[c] += w * p.mean[c];
      if (p.count > 1) variance[c] += w * p.m2[c] / float(p.count - 1);
    }
    out.alpha += w * p.alpha;
    out.albedo += w * p.albedo;
    out.normal += w * p.normal;
    out.emitted += w * p.emitted;
    out.firstHalf += w * (p.count >= 2 ? p.firstHalf : p.mean[0] - p.emitted);
    out.prefix += w * p.prefix;
    if (p.rangeCount > 0) {
      rangeWeight += w;
      out.range += w * p.range;
      out.rangeM2 += w * p.rangeM2 / float(p.rangeCount);
      rangeCount += w * float(p.rangeCount);
      rangeHits += w * float(p.rangeHits);
    }
  }
  const std::uint32_t carried = std::min(std::uint32_t(count + 0.5f), limit);
  if (carried == 0) return false;
  out.count = out.inherited = carried;
  for (int c = 0; c < channels; ++c) out.m2[c] = variance[c] * float(carried - 1);
  out.depth = d;
  out.object = hit ? object : kNoObject;
  if (rangeWeight > 0.0f) {
    out.range /= rangeWeight;
    out.rangeCount = std::max<std::uint32_t>(1, std::uint32_t(rangeCount / rangeWeight + 0.5f));
    out.rangeM2 = out.rangeM2 / rangeWeight * float(out.rangeCount);
    out.rangeHits = hit ? std::min(out.rangeCount, std::uint32_t(rangeHits / rangeWeight + 0.5f)) : 0;
    out.rangeDepth = d;
  }
  return true;
}

}  // namespace

void FrameBuffer::reproject(const Reprojection& r) {
  // The old samples move to the spare buffer and the new ones fill the
  // spare's memory: fresh 40 MB a frame (500x400) would cost more in page
  // faults than the reprojection itself.
  // Every new pixel is written below (the gather), so the spare's stale
  // contents need no clearing first.
  spare_.swap(pixels_);
  pixels_.resize(std::size_t(width_) * height_);
  const std::vector<Pixel>& old = spare_;
  epoch_ = nextEpoch();
  carriesHistory_ = false;
  const Projection from(r.fromCamera, r.fromRegion), to(r.toCamera, r.toRegion);
  if (from.columns * from.rows != old.size() || to.columns * to.rows != pixels_.size()) {
    pixels_.assign(pixels_.size(), emptyPixel());
    return;  // sizes that do not match their regions: nothing to carry
  }
  const InstanceMotions motions(r.placedThen, r.placedNow);
  const Prediction predicted = fillGaps(splatNearest(old, from, to, motions), to);
  const std::uint32_t limit = std::max<std::uint32_t>(r.historyLimit, 1);
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, to.rows), [&](const tbb::blocked_range<std::uint32_t>& rows) {
    for (std::uint32_t y = rows.begin(); y != rows.end(); ++y)
      for (std::uint32_t x = 0; x < to.columns; ++x) {
        const std::size_t i = std::size_t(y) * to.columns + x;
        Pixel out = emptyPixel();
        const Taps<Pixel> taps = historyTaps(old, from, to, motions, predicted, x, y);
        if (taps.total >= kLeastWeight && blendTaps(taps, predicted.depth[i], predicted.object[i], limit, out))
          pixels_[i] = out;
        else
          pixels_[i] = emptyPixel();
      }
  });
  carriesHistory_ = true;
}

}  // namespace tsr::embree
