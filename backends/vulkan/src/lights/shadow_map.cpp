#include "lights/shadow_map.hpp"

#include "resources/render_target.hpp"

#include "tsr/vk/error.hpp"
#include "vk_struct.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace tsr::vk {

ShadowMap::ShadowMap(const Device& device, std::uint32_t size, std::uint32_t layers) : device_(device.handle()) {
  ImageDesc d;
  d.width = d.height = size;
  d.layers = layers;
  d.format = kDepthFormat;
  d.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
  d.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  d.arrayView = true;  // the shader declares sampler2DArrayShadow
  image_ = Image(device, d);
  VkSamplerCreateInfo sci = vkStruct<VkSamplerCreateInfo>(VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO);
  sci.magFilter = VK_FILTER_NEAREST;
  sci.minFilter = VK_FILTER_NEAREST;
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  sci.compareEnable = VK_TRUE;
  sci.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;  // lit when the fragment is no farther than the occluder
  sci.maxLod = 0.0f;
  check(vkCreateSampler(device_, &sci, nullptr, &sampler_), "vkCreateSampler (shadow)");
}

ShadowMap::~ShadowMap() {
  if (sampler_) vkDestroySampler(device_, sampler_, nullptr);
}

namespace {
glm::vec3 upFor(const glm::vec3& d) { return std::abs(d.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0); }
}  // namespace

ShadowProjection directionalShadow(const DirectionalLight& light, const glm::vec3& lo, const glm::vec3& hi,
                                   std::uint32_t mapSize) {
  const glm::vec3 c = 0.5f * (lo + hi);
  const float r = std::max(0.5f * glm::length(hi - lo), 1e-3f);
  const glm::vec3 d = glm::normalize(light.direction);
  const glm::mat4 view = glm::lookAtRH(c - 2.0f * r * d, c, upFor(d));
  const glm::mat4 proj = glm::orthoRH_ZO(-r, r, -r, r, 0.5f * r, 3.5f * r);
  return {proj * view, 1.5f * 2.0f * r / float(mapSize)};
}

ShadowProjection spotShadow(const SpotLight& light, const glm::vec3& lo, const glm::vec3& hi, std::uint32_t mapSize) {
  const glm::vec3 c = 0.5f * (lo + hi);
  const float r = std::max(0.5f * glm::length(hi - lo), 1e-3f);
  const float dist = glm::length(c - light.position);
  const float far = dist + r;
  const float near = std::max(far * 1e-3f, dist - r);
  // Cones wider than 170 degrees are clipped; what lies outside is unshadowed.
  const float fov = std::min(2.0f * light.outerAngle + 0.02f, glm::radians(170.0f));
  const glm::vec3 d = glm::normalize(light.direction);
  const glm::mat4 view = glm::lookAtRH(light.position, light.position + d, upFor(d));
  const glm::mat4 proj = glm::perspectiveRH_ZO(fov, 1.0f, near, far);
  return {proj * view, 1.5f * 2.0f * std::tan(0.5f * fov) / float(mapSize)};
}

}  // namespace tsr::vk
