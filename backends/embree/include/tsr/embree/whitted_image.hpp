#pragma once
// The one-sample image of Renderer::renderWhitted: what a viewport shows
// the moment the camera rests (Schwenk's figure 5.6). Nothing accumulates,
// so it holds only what is shown: 44 bytes a pixel where the path tracer's
// FrameBuffer keeps 160 of running statistics.
#include "tsr/embree/framebuffer.hpp"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace tsr::embree {

class WhittedImage {
 public:
  WhittedImage(std::uint32_t width, std::uint32_t height);

  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }
  // Every pixel rendered for what the key names (a cancelled pass leaves it false).
  bool complete() const { return complete_; }

  // Row-major, region-sized. colour: radiance, alpha 1 where the camera ray
  // hit geometry; depth: camera-space depth, +infinity on a miss; albedo and
  // normal of the first surface, zero on a miss.
  const std::vector<glm::vec4>& colour() const { return colour_; }
  const std::vector<float>& depth() const { return depth_; }
  const std::vector<glm::vec3>& albedo() const { return albedo_; }
  const std::vector<glm::vec3>& normal() const { return normal_; }

 private:
  friend class Renderer;
  std::uint32_t width_, height_;
  std::vector<glm::vec4> colour_;
  std::vector<float> depth_;
  std::vector<glm::vec3> albedo_, normal_;
  std::optional<FrameKey> key_;
  bool complete_ = false;
};

}  // namespace tsr::embree
