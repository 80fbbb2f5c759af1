#pragma once
// A named output a resolve step needs from the frame it was handed (its
// inputs travel beside the colour, from this viewport or from cluster tiles).
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "tsr/med/frame_buffer.hpp"

namespace tsr::med::embree_mediator {

// The output `name`, one entry a pixel; throws std::invalid_argument
// naming `who` and the output when the frame lacks it.
inline const std::vector<glm::vec4>& requiredOutput(const FrameBuffer& frame, const char* name, const char* who) {
  auto it = frame.outputs.find(name);
  if (it == frame.outputs.end() || it->second.size() != frame.colour.size())
    throw std::invalid_argument(std::string(who) + ": the frame has no '" + name + "' output");
  return it->second;
}

// The outputs `names` of `out`, each set to n zeroed pixels, for a
// viewport to write in place.
template <std::size_t N>
std::array<std::vector<glm::vec4>*, N> zeroedOutputs(FrameBuffer& out, const char* const (&names)[N], std::size_t n) {
  std::array<std::vector<glm::vec4>*, N> images{};
  for (std::size_t k = 0; k < N; ++k) {
    images[k] = &out.outputs[names[k]];
    images[k]->assign(n, glm::vec4(0.0f));
  }
  return images;
}

// Each pixel's rgb, or its channel `c`, of an output.
inline std::vector<glm::vec3> rgbOf(const std::vector<glm::vec4>& image) {
  std::vector<glm::vec3> rgb(image.size());
  for (std::size_t i = 0; i < image.size(); ++i) rgb[i] = glm::vec3(image[i]);
  return rgb;
}
inline std::vector<float> channelOf(const std::vector<glm::vec4>& image, int c) {
  std::vector<float> channel(image.size());
  for (std::size_t i = 0; i < image.size(); ++i) channel[i] = image[i][c];
  return channel;
}

}  // namespace tsr::med::embree_mediator
