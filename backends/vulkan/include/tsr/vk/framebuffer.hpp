#pragma once

#include <glm/vec4.hpp>

#include <cstdint>
#include <vector>

namespace tsr::vk {

// What one render of a region produced, row-major with row 0 at the top:
//  - colour: linear radiance; alpha = coverage (1 over opaque geometry, the
//    blended opacity over transparent geometry, the background's alpha elsewhere)
//  - depth: camera-space depth (distance along the view axis, -Z in camera
//    space) of the nearest opaque surface; +infinity where none was drawn.
//    Transparent geometry does not write depth. With MSAA this is the depth
//    of sample 0 (the resolve keeps one sample rather than averaging depths).
// Same conventions as the Embree back-end's FrameBuffer, for compositing.
class FrameBuffer {
 public:
  FrameBuffer(std::uint32_t width, std::uint32_t height);
  // An image made elsewhere (composited, filtered) to present: colour as
  // above, width * height pixels, depth +infinity. Throws Error on a size mismatch.
  FrameBuffer(std::uint32_t width, std::uint32_t height, std::vector<glm::vec4> colour);

  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }

  glm::vec4 colour(std::uint32_t x, std::uint32_t y) const { return colour_[at(x, y)]; }
  float depth(std::uint32_t x, std::uint32_t y) const { return depth_[at(x, y)]; }

  const std::vector<glm::vec4>& colourImage() const { return colour_; }
  const std::vector<float>& depthImage() const { return depth_; }

 private:
  friend class Renderer;
  std::size_t at(std::uint32_t x, std::uint32_t y) const { return std::size_t(y) * width_ + x; }

  std::uint32_t width_;
  std::uint32_t height_;
  std::vector<glm::vec4> colour_;
  std::vector<float> depth_;
};

}  // namespace tsr::vk
