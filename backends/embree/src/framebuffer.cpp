#include "tsr/embree/framebuffer.hpp"

#include "tsr/embree/error.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>

namespace tsr::embree {

FrameBuffer::FrameBuffer(std::uint32_t width, std::uint32_t height) : width_(width), height_(height) {
  if (width == 0 || height == 0) throw Error("frame buffer size must be non-zero");
  reset();
}

FrameBuffer::Pixel FrameBuffer::emptyPixel() {
  Pixel empty;
  empty.depth = std::numeric_limits<float>::infinity();
  return empty;
}

void FrameBuffer::reset() {
  pixels_.assign(std::size_t(width_) * height_, emptyPixel());
  key_.reset();
  carriesHistory_ = false;
  epoch_ = nextEpoch();
}

std::uint64_t FrameBuffer::nextEpoch() {
  static std::atomic<std::uint64_t> epochs{0};
  return epochs.fetch_add(1, std::memory_order_relaxed) + 1;
}

// A jittered sample's depth differs from the pixel centre's by the surface's
// slope across the pixel: 5 % holds all but grazing views, which the
// history then loses, as it loses a surface that truly moved that far.
constexpr float kDepthTolerance = 0.05f;
// The normals of the sample and the history's mean may differ by ~60 deg
// (the mean of a pixel on an edge between two faces).
constexpr float kNormalAgreement = 0.5f;

bool FrameBuffer::continues(const Pixel& p, const PixelSample& s) {
  if (s.hit != std::isfinite(p.depth)) return false;
  if (!s.hit) return true;
  return s.object == p.object && std::abs(s.depth - p.depth) <= kDepthTolerance * p.depth &&
         glm::dot(s.normal, p.normal) >= kNormalAgreement * glm::length(p.normal);
}

void FrameBuffer::accumulate(std::uint32_t x, std::uint32_t y, const PixelSample& s) {
  Pixel& p = pixels_[at(x, y)];
  if (p.inherited != 0 && p.count == p.inherited && !continues(p, s)) [[unlikely]]
    p = emptyPixel();
  const float inv = 1.0f / float(++p.count);
  const glm::vec3 values[kChannels] = {s.direct + s.indirect, s.direct, s.indirect, s.caustic};
  for (int c = 0; c < kChannels; ++c) {
    // Welford: numerically stable running mean and sum of squared deviations.
    glm::vec3 delta = values[c] - p.mean[c];
    p.mean[c] += delta * inv;
    p.m2[c] += delta * (values[c] - p.mean[c]);
  }
  p.alpha += ((s.hit ? 1.0f : 0.0f) - p.alpha) * inv;
  p.albedo += (s.albedo - p.albedo) * inv;
  p.normal += (s.normal - p.normal) * inv;
  p.emitted += (s.emitted - p.emitted) * inv;
  if (s.hit && s.depth <= p.depth) {
    p.depth = s.depth;
    p.object = s.object;
  }
  if (std::has_single_bit(p.count)) {
    p.firstHalf = p.prefix;
    p.prefix = p.mean[0] - p.emitted;
  }
}

std::uint32_t FrameBuffer::firstHalfCount(std::uint32_t x, std::uint32_t y) const {
  const std::uint32_t count = pixels_[at(x, y)].count;
  return count > 0 ? std::bit_floor(count) / 2 : 0;
}

void FrameBuffer::accumulateRange(std::uint32_t x, std::uint32_t y, const glm::vec3& flash, float depth) {
  Pixel& p = pixels_[at(x, y)];
  if (std::isfinite(depth)) p.rangeDepth += (depth - p.rangeDepth) / float(++p.rangeHits);
  const glm::vec3 delta = flash - p.range;
  p.range += delta / float(++p.rangeCount);
  p.rangeM2 += glm::dot(delta, flash - p.range);
}

float FrameBuffer::rangeDepth(std::uint32_t x, std::uint32_t y) const {
  const Pixel& p = pixels_[at(x, y)];
  return p.rangeHits > 0 ? p.rangeDepth : std::numeric_limits<float>::infinity();
}

float FrameBuffer::rangeSpread(std::uint32_t x, std::uint32_t y) const {
  const Pixel& p = pixels_[at(x, y)];
  return p.rangeCount > 1 ? std::sqrt(std::max(0.0f, p.rangeM2) / float(p.rangeCount)) : 0.0f;
}

glm::vec4 FrameBuffer::colour(std::uint32_t x, std::uint32_t y) const {
  const Pixel& p = pixels_[at(x, y)];
  return glm::vec4(p.mean[0], p.alpha);
}

glm::vec3 FrameBuffer::mean(Channel c, std::uint32_t x, std::uint32_t y) const {
  return pixels_[at(x, y)].mean[int(c)];
}

glm::vec3 FrameBuffer::variance(Channel c, std::uint32_t x, std::uint32_t y) const {
  const Pixel& p = pixels_[at(x, y)];
  return p.count > 1 ? p.m2[int(c)] / float(p.count - 1) : glm::vec3(0.0f);
}

std::vector<glm::vec4> FrameBuffer::colourImage() const {
  std::vector<glm::vec4> out(pixels_.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = glm::vec4(pixels_[i].mean[0], pixels_[i].alpha);
  return out;
}

std::vector<float> FrameBuffer::depthImage() const {
  std::vector<float> out(pixels_.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = pixels_[i].depth;
  return out;
}

}  // namespace tsr::embree
