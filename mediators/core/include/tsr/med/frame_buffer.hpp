#pragma once
// What a viewport renders into: RGBA float colour (alpha = coverage) and
// camera-space depth (distance along the view axis, +inf where nothing was
// hit), plus optional named outputs (albedo, normal, variance, ...).
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec4.hpp>

namespace tsr::med {

inline constexpr float kNoDepth = std::numeric_limits<float>::infinity();

// Output names that mean a frame buffer's own colour and depth rather than
// one of its named `outputs`: every back-end fills these.
inline bool isColourOutput(std::string_view name) { return name == "colour" || name == "color"; }
inline bool isDepthOutput(std::string_view name) { return name == "depth"; }

struct FrameBuffer {
  FrameBuffer() = default;
  FrameBuffer(std::uint32_t w, std::uint32_t h)
      : width(w), height(h), colour(std::size_t{w} * h, glm::vec4(0.0f)), depth(std::size_t{w} * h, kNoDepth) {}

  std::size_t index(std::uint32_t x, std::uint32_t y) const { return std::size_t{y} * width + x; }

  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<glm::vec4> colour;  // row 0 at the top
  std::vector<float> depth;
  std::map<std::string, std::vector<glm::vec4>> outputs;  // arbitrary output variables by name
};

}  // namespace tsr::med
