#pragma once

#include "resources/image.hpp"

#include "tsr/vk/device.hpp"
#include "tsr/vk/vocabulary.hpp"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>

namespace tsr::vk {

// One depth layer per shadowed light, sampled with depth comparison.
class ShadowMap {
 public:
  ShadowMap(const Device& device, std::uint32_t size, std::uint32_t layers);
  ~ShadowMap();
  ShadowMap(const ShadowMap&) = delete;
  ShadowMap& operator=(const ShadowMap&) = delete;

  std::uint32_t size() const { return image_.desc().width; }
  std::uint32_t layers() const { return image_.desc().layers; }
  const Image& image() const { return image_; }
  VkSampler sampler() const { return sampler_; }

 private:
  VkDevice device_;
  Image image_;
  VkSampler sampler_ = VK_NULL_HANDLE;
};

// Light view-projection (Vulkan clip space, depth 0..1) that covers the
// bounding sphere of [lo, hi], and the normal offset the shader applies to
// avoid self-shadowing: world units for directional lights, world units per
// unit distance for spot lights.
struct ShadowProjection {
  glm::mat4 viewProj{1.0f};
  float normalOffset = 0.0f;
};
ShadowProjection directionalShadow(const DirectionalLight& light, const glm::vec3& lo, const glm::vec3& hi,
                                   std::uint32_t mapSize);
ShadowProjection spotShadow(const SpotLight& light, const glm::vec3& lo, const glm::vec3& hi, std::uint32_t mapSize);

}  // namespace tsr::vk
