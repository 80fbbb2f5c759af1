#pragma once

#include "bench_scene.hpp"

#include "tsr/vk/device.hpp"

#include <glm/vec4.hpp>

#include <memory>
#include <vector>

namespace tsr::vk::bench {

// The baseline: the least Vulkan that draws the same triangles at the same
// resolution and reads back the same images. One vertex stream, one storage
// buffer of instance matrices, one instanced draw per mesh, a constant-colour
// fragment shader, RGBA32F colour + D32 depth copied to host memory.
class MinimalRenderer {
 public:
  MinimalRenderer(std::shared_ptr<Device> device, const BenchScene& scene, std::uint32_t width, std::uint32_t height);
  ~MinimalRenderer();
  MinimalRenderer(const MinimalRenderer&) = delete;
  MinimalRenderer& operator=(const MinimalRenderer&) = delete;

  void renderFrame();
  const std::vector<glm::vec4>& colour() const { return colour_; }
  const std::vector<float>& depth() const { return depth_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<glm::vec4> colour_;
  std::vector<float> depth_;
};

}  // namespace tsr::vk::bench
