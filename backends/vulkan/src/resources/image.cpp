#include "resources/image.hpp"
#include "resources/device_memory.hpp"

#include "resources/buffer.hpp"

#include "tsr/vk/error.hpp"
#include "vk_struct.hpp"

#include <algorithm>
#include <cstring>
#include <string>
#include <utility>

namespace tsr::vk {

Image::Image(const Device& device, const ImageDesc& desc) : device_(device.handle()), desc_(desc) {
  if (desc.width == 0 || desc.height == 0 || desc.layers == 0) throw Error("image size must be non-zero");
  VkImageCreateInfo ici = vkStruct<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
  ici.imageType = VK_IMAGE_TYPE_2D;
  ici.format = desc.format;
  ici.extent = {desc.width, desc.height, 1};
  if (desc.mipLevels == 0 || desc.mipLevels > mipLevelCount(desc.width, desc.height))
    throw Error("image of " + std::to_string(desc.width) + "x" + std::to_string(desc.height) + " cannot have " +
                std::to_string(desc.mipLevels) + " mip levels");
  ici.mipLevels = desc.mipLevels;
  ici.arrayLayers = desc.layers;
  ici.samples = desc.samples;
  ici.tiling = VK_IMAGE_TILING_OPTIMAL;
  ici.usage = desc.usage;
  ici.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ici.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  check(vkCreateImage(device_, &ici, nullptr, &image_), "vkCreateImage");
  try {
    memory_ = bindNewMemory(device, image_, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, "image");

    VkImageViewCreateInfo vci = vkStruct<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
    vci.image = image_;
    vci.viewType = desc.layers > 1 || desc.arrayView ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
    vci.format = desc.format;
    vci.subresourceRange = {desc.aspect, 0, desc.mipLevels, 0, desc.layers};
    check(vkCreateImageView(device_, &vci, nullptr, &view_), "vkCreateImageView");
    for (std::uint32_t l = 0; l < desc.layers; ++l) {
      vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
      vci.subresourceRange = {desc.aspect, 0, 1, l, 1};
      VkImageView v = VK_NULL_HANDLE;
      check(vkCreateImageView(device_, &vci, nullptr, &v), "vkCreateImageView (layer)");
      layerViews_.push_back(v);
    }
  } catch (...) {
    release();
    throw;
  }
}

Image::~Image() { release(); }

Image::Image(Image&& o) noexcept
    : device_(o.device_),
      desc_(o.desc_),
      image_(std::exchange(o.image_, VK_NULL_HANDLE)),
      memory_(std::exchange(o.memory_, VK_NULL_HANDLE)),
      view_(std::exchange(o.view_, VK_NULL_HANDLE)),
      layerViews_(std::move(o.layerViews_)) {
  o.layerViews_.clear();
}

Image& Image::operator=(Image&& o) noexcept {
  if (this != &o) {
    release();
    device_ = o.device_;
    desc_ = o.desc_;
    image_ = std::exchange(o.image_, VK_NULL_HANDLE);
    memory_ = std::exchange(o.memory_, VK_NULL_HANDLE);
    view_ = std::exchange(o.view_, VK_NULL_HANDLE);
    layerViews_ = std::move(o.layerViews_);
    o.layerViews_.clear();
  }
  return *this;
}

void Image::release() {
  for (VkImageView v : layerViews_) vkDestroyImageView(device_, v, nullptr);
  layerViews_.clear();
  if (view_) vkDestroyImageView(device_, view_, nullptr);
  if (image_) vkDestroyImage(device_, image_, nullptr);
  if (memory_) vkFreeMemory(device_, memory_, nullptr);
  view_ = VK_NULL_HANDLE;
  image_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags srcStage, VkAccessFlags srcAccess, VkPipelineStageFlags dstStage,
                  VkAccessFlags dstAccess, std::uint32_t layers, std::uint32_t firstLevel, std::uint32_t levels) {
  VkImageMemoryBarrier b = vkStruct<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
  b.srcAccessMask = srcAccess;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {aspect, firstLevel, levels, 0, layers};
  vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

std::uint32_t mipLevelCount(std::uint32_t width, std::uint32_t height) {
  std::uint32_t levels = 1;
  for (std::uint32_t side = std::max(width, height); side > 1; side /= 2) ++levels;
  return levels;
}

namespace {

// Level `to` from level `to - 1` by a linear blit; the level above goes
// from TRANSFER_DST to TRANSFER_SRC first.
void blitLevel(VkCommandBuffer cmd, VkImage image, std::uint32_t width, std::uint32_t height, std::uint32_t to) {
  imageBarrier(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
               VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT, 1, to - 1, 1);
  const auto side = [](std::uint32_t s, std::uint32_t level) { return std::int32_t(std::max(s >> level, 1u)); };
  VkImageBlit blit{};
  blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, to - 1, 0, 1};
  blit.srcOffsets[1] = {side(width, to - 1), side(height, to - 1), 1};
  blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, to, 0, 1};
  blit.dstOffsets[1] = {side(width, to), side(height, to), 1};
  vkCmdBlitImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                 &blit, VK_FILTER_LINEAR);
}

}  // namespace

Image uploadImage(const Device& device, std::uint32_t width, std::uint32_t height, VkFormat format, const void* bytes,
                  VkDeviceSize size, bool mipmapped) {
  VkFormatProperties props;
  vkGetPhysicalDeviceFormatProperties(device.physicalDevice(), format, &props);
  if (!(props.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT))
    throw Error("texture format " + std::to_string(format) + " cannot be sampled with linear filtering on " +
                device.name());
  constexpr VkFormatFeatureFlags kBlit = VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT;
  const bool chain = mipmapped && (props.optimalTilingFeatures & kBlit) == kBlit;
  ImageDesc desc;
  desc.width = width;
  desc.height = height;
  desc.format = format;
  desc.mipLevels = chain ? mipLevelCount(width, height) : 1;
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  if (desc.mipLevels > 1) desc.usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  Image image(device, desc);
  Buffer staging(device, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, Buffer::kHost);
  std::memcpy(staging.mapped(), bytes, size);
  device.submitAndWait([&](VkCommandBuffer cmd) {
    imageBarrier(cmd, image.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                 VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {width, height, 1};
    vkCmdCopyBufferToImage(cmd, staging.handle(), image.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
    const std::uint32_t last = desc.mipLevels - 1;
    for (std::uint32_t level = 1; level <= last; ++level) blitLevel(cmd, image.handle(), width, height, level);
    // The levels blitted from are TRANSFER_SRC, the last (or only) one TRANSFER_DST.
    if (last > 0)
      imageBarrier(cmd, image.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                   VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT, 1, 0,
                   last);
    imageBarrier(cmd, image.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT, 1, last, 1);
  });
  return image;
}

}  // namespace tsr::vk
