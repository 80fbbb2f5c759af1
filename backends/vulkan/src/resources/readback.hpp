#pragma once
// Bringing a pass's result to the host, shared by the shaded pass and the id
// pass: both end with a colour (or id) attachment and a depth attachment,
// copied into host-visible buffers after the pass, then depth turned from
// the reversed-Z buffer into distances along the view axis.
#include <span>

#include <vulkan/vulkan.h>

#include "resources/buffer.hpp"
#include "resources/image.hpp"
#include "tsr/vk/vocabulary.hpp"

namespace tsr::vk {

// Records, after the pass that wrote them (colour in COLOR_ATTACHMENT_OPTIMAL,
// depth in DEPTH_ATTACHMENT_OPTIMAL), the copies of both images into the
// buffers and the barrier that makes them visible to the host.
void recordReadback(VkCommandBuffer cmd, const Image& colour, const Image& depth, const Buffer& colourOut,
                    const Buffer& depthOut, std::uint32_t width, std::uint32_t height);

// Once the commands completed: the depth buffer as linear depths.
void readLinearDepth(const Buffer& depthOut, const Camera& camera, std::span<float> out);

}  // namespace tsr::vk
