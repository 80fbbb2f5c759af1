#include "tsr/embree/framebuffer.hpp"

#include "tsr/embree/error.hpp"

#include <algorithm>
#include <limits>

namespace tsr::embree {

FrameBuffer::FrameBuffer(std::uint32_t width, std::uint32_t height) : width_(width), height_(height) {
  if (width == 0 || height == 0) throw Error("frame buffer size must be non-zero");
  reset();
}

void FrameBuffer::reset() {
  std::size_t n = std::size_t(width_) * height_;
  count_.assign(n, 0);
  alpha_.assign(n, 0.0f);
  for (int c = 0; c < 3; ++c) {
    mean_[c].assign(n, glm::vec3(0.0f));
    m2_[c].assign(n, glm::vec3(0.0f));
  }
  depth_.assign(n, std::numeric_limits<float>::infinity());
  albedo_.assign(n, glm::vec3(0.0f));
  normal_.assign(n, glm::vec3(0.0f));
  key_.reset();
}

void FrameBuffer::accumulate(std::uint32_t x, std::uint32_t y, const PixelSample& s) {
  std::size_t i = at(x, y);
  float n = float(++count_[i]);
  float inv = 1.0f / n;
  const glm::vec3 values[3] = {s.direct + s.indirect, s.direct, s.indirect};
  for (int c = 0; c < 3; ++c) {
    // Welford: numerically stable running mean and sum of squared deviations.
    glm::vec3 delta = values[c] - mean_[c][i];
    mean_[c][i] += delta * inv;
    m2_[c][i] += delta * (values[c] - mean_[c][i]);
  }
  alpha_[i] += ((s.hit ? 1.0f : 0.0f) - alpha_[i]) * inv;
  albedo_[i] += (s.albedo - albedo_[i]) * inv;
  normal_[i] += (s.normal - normal_[i]) * inv;
  if (s.hit) depth_[i] = std::min(depth_[i], s.depth);
}

glm::vec4 FrameBuffer::colour(std::uint32_t x, std::uint32_t y) const {
  std::size_t i = at(x, y);
  return glm::vec4(mean_[0][i], alpha_[i]);
}

glm::vec3 FrameBuffer::mean(Channel c, std::uint32_t x, std::uint32_t y) const { return mean_[int(c)][at(x, y)]; }

glm::vec3 FrameBuffer::variance(Channel c, std::uint32_t x, std::uint32_t y) const {
  std::size_t i = at(x, y);
  return count_[i] > 1 ? m2_[int(c)][i] / float(count_[i] - 1) : glm::vec3(0.0f);
}

std::vector<glm::vec4> FrameBuffer::colourImage() const {
  std::vector<glm::vec4> out(count_.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = glm::vec4(mean_[0][i], alpha_[i]);
  return out;
}

}  // namespace tsr::embree
