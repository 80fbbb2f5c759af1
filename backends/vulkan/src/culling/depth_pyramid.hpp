#pragma once

#include "resources/compute_pipeline.hpp"

#include "tsr/vk/device.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

namespace tsr::vk {

// A hierarchical depth buffer for occlusion tests: R32F, level 0 the depth
// attachment padded to powers of two (padding = the near plane), each
// further level half the size, so texel (x >> L, y >> L) of level L holds
// the farthest depth of every pixel it covers. Reduction by a min-filtering sampler (zeux's niagara builds
// its pyramid the same way). Kept in GENERAL layout.
class DepthPyramid {
 public:
  explicit DepthPyramid(const Device& device);
  ~DepthPyramid();
  DepthPyramid(const DepthPyramid&) = delete;
  DepthPyramid& operator=(const DepthPyramid&) = delete;

  // Sizes the pyramid for a depth attachment (recreated when size, samples
  // or view change). Call before recording anything that binds view().
  void ensure(VkImageView depthView, std::uint32_t width, std::uint32_t height, VkSampleCountFlagBits samples);
  // Records the reduction; the depth image must be in SHADER_READ_ONLY_OPTIMAL.
  // Ends with the pyramid readable by compute shaders.
  void record(VkCommandBuffer cmd);

  VkImageView view() const { return view_; }
  VkSampler fetchSampler() const { return nearest_; }

 private:
  void release();

  const Device& device_;
  ComputePipeline reduce_;
  ComputePipeline reduceMs_;
  ComputePipeline downsample_;
  VkSampler min_ = VK_NULL_HANDLE;
  VkSampler nearest_ = VK_NULL_HANDLE;

  VkImage image_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  std::vector<VkImageView> levelViews_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> sets_;  // [0] reduces the depth, [L] makes level L
  std::vector<VkExtent2D> sizes_;
  VkImageView depthView_ = VK_NULL_HANDLE;
  VkSampleCountFlagBits samples_ = VK_SAMPLE_COUNT_1_BIT;
  VkExtent2D depthSize_{0, 0};
};

}  // namespace tsr::vk
