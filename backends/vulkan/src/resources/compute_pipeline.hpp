#pragma once

#include "tsr/vk/device.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>

namespace tsr::vk {

// A compute pipeline with its own layout: one descriptor set whose binding
// i has type bindings[i], and push constants of pushBytes. Owner; not movable.
class ComputePipeline {
 public:
  ComputePipeline(const Device& device, std::span<const std::uint32_t> spirv,
                  std::span<const VkDescriptorType> bindings, std::uint32_t pushBytes);
  ~ComputePipeline();
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;

  VkPipeline handle() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_; }
  VkDescriptorSetLayout setLayout() const { return setLayout_; }

  // Binds the pipeline and its set, pushes `push`, dispatches.
  void dispatch(VkCommandBuffer cmd, VkDescriptorSet set, const void* push, std::uint32_t x, std::uint32_t y = 1) const;

 private:
  VkDevice device_;
  std::uint32_t pushBytes_;
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

// A compute-to-compute (or to indirect-draw) execution and memory dependency.
void computeBarrier(VkCommandBuffer cmd, VkPipelineStageFlags dstStage, VkAccessFlags dstAccess);

}  // namespace tsr::vk
