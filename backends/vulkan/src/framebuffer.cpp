#include "tsr/vk/framebuffer.hpp"

#include "tsr/vk/error.hpp"

#include <limits>

namespace tsr::vk {

FrameBuffer::FrameBuffer(std::uint32_t width, std::uint32_t height) : width_(width), height_(height) {
  if (width == 0 || height == 0) throw Error("frame buffer size must be non-zero");
  colour_.assign(std::size_t(width) * height, glm::vec4(0.0f));
  depth_.assign(std::size_t(width) * height, std::numeric_limits<float>::infinity());
}

FrameBuffer::FrameBuffer(std::uint32_t width, std::uint32_t height, std::vector<glm::vec4> colour)
    : FrameBuffer(width, height) {
  if (colour.size() != colour_.size()) throw Error("frame buffer colour has the wrong number of pixels");
  colour_ = std::move(colour);
}

}  // namespace tsr::vk
