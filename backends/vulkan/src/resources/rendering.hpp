#pragma once
// Dynamic rendering as every pass here begins it: one colour attachment (or
// none) and one depth attachment over a whole width x height, with the
// viewport and scissor covering all of it.
#include <cstdint>

#include <vulkan/vulkan.h>

namespace tsr::vk {

// An attachment in `layout` that is cleared to `clear` (or loaded) and
// stored (or, with `store` false, left undefined after the pass).
VkRenderingAttachmentInfo renderingAttachment(VkImageView view, VkImageLayout layout, bool load, VkClearValue clear,
                                              bool store = true);

// `colour` may be null (depth only).
void beginRendering(VkCommandBuffer cmd, std::uint32_t width, std::uint32_t height,
                    const VkRenderingAttachmentInfo* colour, const VkRenderingAttachmentInfo& depth);

}  // namespace tsr::vk
