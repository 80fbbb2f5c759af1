#include "resources/rendering.hpp"

#include "vk_struct.hpp"

namespace tsr::vk {

VkRenderingAttachmentInfo renderingAttachment(VkImageView view, VkImageLayout layout, bool load, VkClearValue clear,
                                              bool store) {
  VkRenderingAttachmentInfo a = vkStruct<VkRenderingAttachmentInfo>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO);
  a.imageView = view;
  a.imageLayout = layout;
  a.loadOp = load ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
  a.storeOp = store ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
  a.clearValue = clear;
  return a;
}

void beginRendering(VkCommandBuffer cmd, std::uint32_t width, std::uint32_t height,
                    const VkRenderingAttachmentInfo* colour, const VkRenderingAttachmentInfo& depth) {
  VkRenderingInfo ri = vkStruct<VkRenderingInfo>(VK_STRUCTURE_TYPE_RENDERING_INFO);
  ri.renderArea = {{0, 0}, {width, height}};
  ri.layerCount = 1;
  ri.colorAttachmentCount = colour ? 1 : 0;
  ri.pColorAttachments = colour;
  ri.pDepthAttachment = &depth;
  vkCmdBeginRendering(cmd, &ri);
  const VkViewport viewport{0.0f, 0.0f, float(width), float(height), 0.0f, 1.0f};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &ri.renderArea);
}

}  // namespace tsr::vk
