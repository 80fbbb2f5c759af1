#include "resources/render_target.hpp"

#include "tsr/vk/error.hpp"

namespace tsr::vk {

namespace {
bool supports(const Device& device, VkFormat format, VkSampleCountFlagBits samples, VkFormatFeatureFlags features,
              VkImageUsageFlags usage) {
  VkFormatProperties props;
  vkGetPhysicalDeviceFormatProperties(device.physicalDevice(), format, &props);
  if ((props.optimalTilingFeatures & features) != features) return false;
  VkImageFormatProperties ifp;
  if (vkGetPhysicalDeviceImageFormatProperties(device.physicalDevice(), format, VK_IMAGE_TYPE_2D,
                                               VK_IMAGE_TILING_OPTIMAL, usage, 0, &ifp) != VK_SUCCESS)
    return false;
  return (ifp.sampleCounts & samples) != 0;
}
}  // namespace

VkFormat chooseColourFormat(const Device& device, VkSampleCountFlagBits samples) {
  for (VkFormat f : {VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT}) {
    if (supports(device, f, samples,
                 VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT |
                     VK_FORMAT_FEATURE_TRANSFER_SRC_BIT,
                 VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT))
      return f;
  }
  throw Error("no blendable float colour format with " + std::to_string(int(samples)) + " samples on " + device.name());
}

RenderTarget::RenderTarget(const Device& device, std::uint32_t w, std::uint32_t h, VkFormat colourFormat_,
                           VkSampleCountFlagBits samples_)
    : width(w), height(h), colourFormat(colourFormat_), samples(samples_) {
  if (!supports(device, kDepthFormat, samples, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT,
                VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT))
    throw Error("D32_SFLOAT depth with " + std::to_string(int(samples)) + " samples is not supported on " +
                device.name());
  const bool ms = samples != VK_SAMPLE_COUNT_1_BIT;
  ImageDesc c;
  c.width = w;
  c.height = h;
  c.format = colourFormat;
  c.samples = samples;
  c.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (ms ? 0 : VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  colour = Image(device, c);
  ImageDesc d = c;
  d.format = kDepthFormat;
  d.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
  // Sampled: guided rendering builds its depth pyramid from it.
  d.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
            (ms ? 0 : VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  depth = Image(device, d);
  if (ms) {
    c.samples = d.samples = VK_SAMPLE_COUNT_1_BIT;
    c.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    d.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    colourResolve = Image(device, c);
    depthResolve = Image(device, d);
  }
  const VkDeviceSize pixels = VkDeviceSize(w) * h;
  const VkDeviceSize texel = colourFormat == VK_FORMAT_R32G32B32A32_SFLOAT ? 16 : 8;
  // Cached memory makes CPU reads fast; not every device offers it with coherence.
  auto readback = [&](VkDeviceSize size) {
    try {
      return Buffer(device, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, Buffer::kHost | VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
    } catch (const Error&) {
      return Buffer(device, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, Buffer::kHost);
    }
  };
  colourReadback = readback(pixels * texel);
  depthReadback = readback(pixels * 4);
}

}  // namespace tsr::vk
