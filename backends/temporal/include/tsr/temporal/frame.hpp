#pragma once
// One frame of a sequence as the temporal methods see it: linear RGB,
// three floats per pixel, row 0 at the top.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tsr::temporal {

struct Frame {
  Frame() = default;
  Frame(std::uint32_t w, std::uint32_t h) : width(w), height(h), rgb(std::size_t{w} * h * 3, 0.0f) {}

  std::size_t pixels() const { return std::size_t{width} * height; }

  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<float> rgb;
};

// Throws std::invalid_argument unless every frame has the same non-empty
// size and rgb holds exactly 3 floats per pixel, all finite.
void checkSequence(const std::vector<Frame>& frames);

}  // namespace tsr::temporal
