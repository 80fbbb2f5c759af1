#pragma once

#include "tsr/vk/device.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <vector>

namespace tsr::vk {

struct PipelineDesc {
  VkPipelineLayout layout = VK_NULL_HANDLE;
  std::span<const std::uint32_t> vertexSpirv;
  std::span<const std::uint32_t> fragmentSpirv;  // empty: depth-only
  std::uint32_t vertexStreams = 3;               // position, normal, uv (separate bindings)
  bool normals = true;                           // false: the normal stream is bound but not read
  VkFormat colourFormat = VK_FORMAT_UNDEFINED;   // UNDEFINED: no colour attachment
  VkFormat depthFormat = VK_FORMAT_D32_SFLOAT;
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  VkCompareOp depthCompare = VK_COMPARE_OP_GREATER;
  bool depthWrite = true;
  bool blend = false;  // "over" with straight alpha
  // colour = source 0 + destination * source 1 (per channel), alpha likewise
  // with source 1's alpha: a medium's light over what it transmits.
  bool dualSourceBlend = false;
  bool depthBias = false;  // shadow maps
  VkCullModeFlags cull = VK_CULL_MODE_NONE;
  VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;  // lists only (indexed, one pixel wide)
  std::vector<std::uint32_t> fragmentConstants;                        // specialisation constant i = value i
};

// A graphics pipeline for dynamic rendering with dynamic viewport/scissor
// (and depth bias when enabled). Move-only owner.
class Pipeline {
 public:
  Pipeline() = default;
  Pipeline(const Device& device, const PipelineDesc& desc);
  ~Pipeline();
  Pipeline(Pipeline&& other) noexcept;
  Pipeline& operator=(Pipeline&& other) noexcept;
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;

  VkPipeline handle() const { return pipeline_; }
  explicit operator bool() const { return pipeline_ != VK_NULL_HANDLE; }

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

}  // namespace tsr::vk
