#pragma once

#include "tsr/vk/device.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

namespace tsr::vk {

struct ImageDesc {
  std::uint32_t width = 1;
  std::uint32_t height = 1;
  std::uint32_t layers = 1;
  std::uint32_t mipLevels = 1;  // view() sees them all, layerView() the first
  VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  VkImageUsageFlags usage = 0;
  VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
  bool arrayView = false;  // view() is 2D_ARRAY even for one layer
};

// A 2D (array) image in device memory with a view of all layers (2D_ARRAY
// when layers > 1 or arrayView) and one 2D view per layer for rendering into it. Move-only.
class Image {
 public:
  Image() = default;
  Image(const Device& device, const ImageDesc& desc);
  ~Image();
  Image(Image&& other) noexcept;
  Image& operator=(Image&& other) noexcept;
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;

  VkImage handle() const { return image_; }
  VkImageView view() const { return view_; }
  VkImageView layerView(std::uint32_t layer) const { return layerViews_[layer]; }
  const ImageDesc& desc() const { return desc_; }
  explicit operator bool() const { return image_ != VK_NULL_HANDLE; }

 private:
  void release();

  VkDevice device_ = VK_NULL_HANDLE;
  ImageDesc desc_;
  VkImage image_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  std::vector<VkImageView> layerViews_;
};

// A sampled image filled from host memory (its layout then
// SHADER_READ_ONLY_OPTIMAL); waits for the copy. Throws when the format
// cannot be sampled with linear filtering. `mipmapped`: the full chain of
// mip levels, each a linear (for sRGB formats, linear-light) 2x2 reduction
// of the one above, made by the device's blits where it can blit the format
// (else one level), so a minified texture averages instead of aliasing.
Image uploadImage(const Device& device, std::uint32_t width, std::uint32_t height, VkFormat format, const void* bytes,
                  VkDeviceSize size, bool mipmapped = false);

// How many levels a full mip chain of a width x height image has.
std::uint32_t mipLevelCount(std::uint32_t width, std::uint32_t height);

// One image memory barrier over the given layers and mip levels (all by default).
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags srcStage, VkAccessFlags srcAccess, VkPipelineStageFlags dstStage,
                  VkAccessFlags dstAccess, std::uint32_t layers = 1, std::uint32_t firstLevel = 0,
                  std::uint32_t levels = VK_REMAINING_MIP_LEVELS);

}  // namespace tsr::vk
