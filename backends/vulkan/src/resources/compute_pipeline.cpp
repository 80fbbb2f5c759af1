#include "resources/compute_pipeline.hpp"

#include "tsr/vk/error.hpp"
#include "vk_struct.hpp"

#include <vector>

namespace tsr::vk {

ComputePipeline::ComputePipeline(const Device& device, std::span<const std::uint32_t> spirv,
                                 std::span<const VkDescriptorType> bindings, std::uint32_t pushBytes)
    : device_(device.handle()), pushBytes_(pushBytes) {
  std::vector<VkDescriptorSetLayoutBinding> b(bindings.size());
  for (std::uint32_t i = 0; i < b.size(); ++i) b[i] = {i, bindings[i], 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  VkDescriptorSetLayoutCreateInfo lci =
      vkStruct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
  lci.bindingCount = std::uint32_t(b.size());
  lci.pBindings = b.data();
  check(vkCreateDescriptorSetLayout(device_, &lci, nullptr, &setLayout_), "vkCreateDescriptorSetLayout (compute)");

  VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes};
  VkPipelineLayoutCreateInfo pci = vkStruct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
  pci.setLayoutCount = 1;
  pci.pSetLayouts = &setLayout_;
  pci.pushConstantRangeCount = pushBytes ? 1 : 0;
  pci.pPushConstantRanges = &push;
  VkShaderModule module = VK_NULL_HANDLE;
  try {
    check(vkCreatePipelineLayout(device_, &pci, nullptr, &layout_), "vkCreatePipelineLayout (compute)");
    VkShaderModuleCreateInfo mci = vkStruct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
    mci.codeSize = spirv.size_bytes();
    mci.pCode = spirv.data();
    check(vkCreateShaderModule(device_, &mci, nullptr, &module), "vkCreateShaderModule (compute)");
    VkComputePipelineCreateInfo cci =
        vkStruct<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
    cci.stage = vkStruct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
    cci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    cci.stage.module = module;
    cci.stage.pName = "main";
    cci.layout = layout_;
    check(vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &cci, nullptr, &pipeline_), "vkCreateComputePipelines");
  } catch (...) {
    if (module) vkDestroyShaderModule(device_, module, nullptr);
    if (layout_) vkDestroyPipelineLayout(device_, layout_, nullptr);
    vkDestroyDescriptorSetLayout(device_, setLayout_, nullptr);
    throw;
  }
  vkDestroyShaderModule(device_, module, nullptr);
}

ComputePipeline::~ComputePipeline() {
  vkDestroyPipeline(device_, pipeline_, nullptr);
  vkDestroyPipelineLayout(device_, layout_, nullptr);
  vkDestroyDescriptorSetLayout(device_, setLayout_, nullptr);
}

void ComputePipeline::dispatch(VkCommandBuffer cmd, VkDescriptorSet set, const void* push, std::uint32_t x,
                               std::uint32_t y) const {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set, 0, nullptr);
  if (pushBytes_) vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes_, push);
  vkCmdDispatch(cmd, x, y, 1);
}

void computeBarrier(VkCommandBuffer cmd, VkPipelineStageFlags dstStage, VkAccessFlags dstAccess) {
  VkMemoryBarrier b = vkStruct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
  b.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  b.dstAccessMask = dstAccess;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, dstStage, 0, 1, &b, 0, nullptr, 0, nullptr);
}

}  // namespace tsr::vk
