#include "culling/depth_pyramid.hpp"
#include "resources/device_memory.hpp"

#include "spirv.hpp"

#include "tsr/vk/error.hpp"
#include "vk_struct.hpp"

#include <algorithm>

namespace tsr::vk {

namespace {

constexpr VkDescriptorType kReduceBindings[] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                                VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};

struct Push {
  std::uint32_t size[4];
  std::uint32_t below;
  std::uint32_t pad[3];
};

VkSampler createSampler(VkDevice device, VkFilter filter, const VkSamplerReductionModeCreateInfo* reduction) {
  VkSamplerCreateInfo sci = vkStruct<VkSamplerCreateInfo>(VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO);
  sci.pNext = reduction;
  sci.magFilter = sci.minFilter = filter;
  sci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  sci.maxLod = VK_LOD_CLAMP_NONE;
  VkSampler s = VK_NULL_HANDLE;
  check(vkCreateSampler(device, &sci, nullptr, &s), "vkCreateSampler (depth pyramid)");
  return s;
}

void pyramidBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkAccessFlags srcAccess,
                    VkPipelineStageFlags srcStage) {
  VkImageMemoryBarrier b = vkStruct<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
  b.srcAccessMask = srcAccess;
  b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
  b.oldLayout = from;
  b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, VK_REMAINING_MIP_LEVELS, 0, 1};
  vkCmdPipelineBarrier(cmd, srcStage, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0, nullptr, 1, &b);
}

}  // namespace

DepthPyramid::DepthPyramid(const Device& device)
    : device_(device),
      reduce_(device, spirv::depth_reduce_comp, kReduceBindings, sizeof(Push)),
      reduceMs_(device, spirv::depth_reduce_ms_comp, kReduceBindings, sizeof(Push)),
      downsample_(device, spirv::depth_downsample_comp, kReduceBindings, sizeof(Push)) {
  VkSamplerReductionModeCreateInfo reduction =
      vkStruct<VkSamplerReductionModeCreateInfo>(VK_STRUCTURE_TYPE_SAMPLER_REDUCTION_MODE_CREATE_INFO);
  reduction.reductionMode = VK_SAMPLER_REDUCTION_MODE_MIN;
  min_ = createSampler(device.handle(), VK_FILTER_LINEAR, &reduction);
  nearest_ = createSampler(device.handle(), VK_FILTER_NEAREST, nullptr);
}

DepthPyramid::~DepthPyramid() {
  release();
  vkDestroySampler(device_.handle(), min_, nullptr);
  vkDestroySampler(device_.handle(), nearest_, nullptr);
}

void DepthPyramid::release() {
  VkDevice dev = device_.handle();
  if (pool_) vkDestroyDescriptorPool(dev, pool_, nullptr);
  for (VkImageView v : levelViews_) vkDestroyImageView(dev, v, nullptr);
  if (view_) vkDestroyImageView(dev, view_, nullptr);
  if (image_) vkDestroyImage(dev, image_, nullptr);
  if (memory_) vkFreeMemory(dev, memory_, nullptr);
  pool_ = VK_NULL_HANDLE;
  levelViews_.clear();
  view_ = VK_NULL_HANDLE;
  image_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  sets_.clear();
  sizes_.clear();
  depthView_ = VK_NULL_HANDLE;
  depthSize_ = {0, 0};
}

void DepthPyramid::ensure(VkImageView depthView, std::uint32_t width, std::uint32_t height,
                          VkSampleCountFlagBits samples) {
  if (depthView == depthView_ && samples == samples_ && depthSize_.width == width && depthSize_.height == height)
    return;
  release();
  VkDevice dev = device_.handle();
  auto pow2 = [](std::uint32_t v) {
    std::uint32_t p = 1;
    while (p < v) p *= 2;
    return p;
  };
  for (VkExtent2D e{pow2(width), pow2(height)};; e = {std::max(1u, e.width / 2), std::max(1u, e.height / 2)}) {
    sizes_.push_back(e);
    if (e.width == 1 && e.height == 1) break;
  }
  const auto levels = std::uint32_t(sizes_.size());
  VkImageCreateInfo ici = vkStruct<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
  ici.imageType = VK_IMAGE_TYPE_2D;
  ici.format = VK_FORMAT_R32_SFLOAT;
  ici.extent = {sizes_[0].width, sizes_[0].height, 1};
  ici.mipLevels = levels;
  ici.arrayLayers = 1;
  ici.samples = VK_SAMPLE_COUNT_1_BIT;
  ici.tiling = VK_IMAGE_TILING_OPTIMAL;
  ici.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  check(vkCreateImage(dev, &ici, nullptr, &image_), "vkCreateImage (depth pyramid)");
  memory_ = bindNewMemory(device_, image_, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, "depth pyramid");
  VkImageViewCreateInfo vci = vkStruct<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
  vci.image = image_;
  vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vci.format = VK_FORMAT_R32_SFLOAT;
  vci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, levels, 0, 1};
  check(vkCreateImageView(dev, &vci, nullptr, &view_), "vkCreateImageView (depth pyramid)");
  for (std::uint32_t l = 0; l < levels; ++l) {
    vci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, l, 1, 0, 1};
    levelViews_.push_back(VK_NULL_HANDLE);
    check(vkCreateImageView(dev, &vci, nullptr, &levelViews_.back()), "vkCreateImageView (pyramid level)");
  }

  const VkDescriptorPoolSize poolSizes[2] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, levels},
                                             {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, levels}};
  VkDescriptorPoolCreateInfo dpci = vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
  dpci.maxSets = levels;
  dpci.poolSizeCount = 2;
  dpci.pPoolSizes = poolSizes;
  check(vkCreateDescriptorPool(dev, &dpci, nullptr, &pool_), "vkCreateDescriptorPool (depth pyramid)");
  sets_.resize(levels);
  for (std::uint32_t l = 0; l < levels; ++l) {
    const bool ms = samples != VK_SAMPLE_COUNT_1_BIT;
    VkDescriptorSetLayout layout = l > 0 ? downsample_.setLayout() : ms ? reduceMs_.setLayout() : reduce_.setLayout();
    VkDescriptorSetAllocateInfo ai =
        vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
    ai.descriptorPool = pool_;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &layout;
    check(vkAllocateDescriptorSets(dev, &ai, &sets_[l]), "vkAllocateDescriptorSets (depth pyramid)");
    const VkDescriptorImageInfo src =
        l == 0 ? VkDescriptorImageInfo{nearest_, depthView, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}
               : VkDescriptorImageInfo{min_, view_, VK_IMAGE_LAYOUT_GENERAL};
    const VkDescriptorImageInfo dst{VK_NULL_HANDLE, levelViews_[l], VK_IMAGE_LAYOUT_GENERAL};
    VkWriteDescriptorSet w[2] = {vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET),
                                 vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET)};
    for (std::uint32_t b = 0; b < 2; ++b) {
      w[b].dstSet = sets_[l];
      w[b].dstBinding = b;
      w[b].descriptorCount = 1;
      w[b].descriptorType = kReduceBindings[b];
      w[b].pImageInfo = b == 0 ? &src : &dst;
    }
    vkUpdateDescriptorSets(dev, 2, w, 0, nullptr);
  }
  depthView_ = depthView;
  samples_ = samples;
  depthSize_ = {width, height};
}

void DepthPyramid::record(VkCommandBuffer cmd) {
  pyramidBarrier(cmd, image_, VK_IMAGE_LAYOUT_UNDEFINED, 0, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT);
  Push push{
      {sizes_[0].width, sizes_[0].height, depthSize_.width, depthSize_.height}, std::uint32_t(samples_), {0, 0, 0}};
  const ComputePipeline& first = samples_ != VK_SAMPLE_COUNT_1_BIT ? reduceMs_ : reduce_;
  first.dispatch(cmd, sets_[0], &push, (sizes_[0].width + 7) / 8, (sizes_[0].height + 7) / 8);
  for (std::uint32_t l = 1; l < sizes_.size(); ++l) {
    computeBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    push = {{sizes_[l].width, sizes_[l].height, sizes_[l - 1].width, sizes_[l - 1].height}, l - 1, {0, 0, 0}};
    downsample_.dispatch(cmd, sets_[l], &push, (sizes_[l].width + 7) / 8, (sizes_[l].height + 7) / 8);
  }
  computeBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
}

}  // namespace tsr::vk
