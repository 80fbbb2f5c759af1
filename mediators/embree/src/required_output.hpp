#pragma once
// A named output a resolve step needs from the frame it was handed (its
// inputs travel beside the colour, from this viewport or from cluster tiles).
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

}  // namespace tsr::med::embree_mediator
