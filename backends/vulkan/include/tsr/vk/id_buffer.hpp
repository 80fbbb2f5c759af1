#pragma once

#include <cstdint>
#include <vector>

namespace tsr::vk {

// What an id pass produced for one region, row-major with row 0 at the top:
// per pixel the object id (Scene::setInstanceObject) of the nearest opaque
// instance covering the pixel centre, kNoObject where none does, and its
// camera-space depth (+infinity where none).
inline constexpr std::uint32_t kNoObject = 0;

struct IdBuffer {
  IdBuffer(std::uint32_t w, std::uint32_t h)
      : width(w), height(h), ids(std::size_t(w) * h), depth(std::size_t(w) * h) {}
  std::size_t index(std::uint32_t x, std::uint32_t y) const { return std::size_t(y) * width + x; }

  std::uint32_t width;
  std::uint32_t height;
  std::vector<std::uint32_t> ids;
  std::vector<float> depth;
};

}  // namespace tsr::vk
