#pragma once

#include "resources/buffer.hpp"
#include "resources/image.hpp"

#include "tsr/vk/device.hpp"

#include <cstdint>

namespace tsr::vk {

constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

// Float colour format for offscreen targets: RGBA32F where the device can
// blend into it and multisample it with `samples`, else RGBA16F.
VkFormat chooseColourFormat(const Device& device, VkSampleCountFlagBits samples);

// Offscreen colour + depth attachments (multisampled when samples > 1, with
// single-sample resolve images) and host buffers the resolved images are
// copied into for readback.
struct RenderTarget {
  RenderTarget(const Device& device, std::uint32_t width, std::uint32_t height, VkFormat colourFormat,
               VkSampleCountFlagBits samples);

  bool multisampled() const { return samples != VK_SAMPLE_COUNT_1_BIT; }
  const Image& resolvedColour() const { return multisampled() ? colourResolve : colour; }
  const Image& resolvedDepth() const { return multisampled() ? depthResolve : depth; }

  std::uint32_t width;
  std::uint32_t height;
  VkFormat colourFormat;
  VkSampleCountFlagBits samples;
  Image colour;
  Image depth;
  Image colourResolve;
  Image depthResolve;
  Buffer colourReadback;
  Buffer depthReadback;
};

}  // namespace tsr::vk
