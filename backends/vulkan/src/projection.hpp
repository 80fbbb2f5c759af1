#pragma once
// The shared camera in Vulkan's clip space: the off-axis projection of a
// region's sub-window with reversed depth, and the way back from depth.
#include <glm/mat4x4.hpp>

#include "tsr/vk/vocabulary.hpp"

namespace tsr::vk {

// Vulkan clip-space projection of the sub-window that `region` cuts out of
// the full image (off-axis), with reversed depth: near -> 1, far -> 0.
glm::mat4 projection(const Camera& camera, const Region& region);

// The frame's viewport record for a target of w x h pixels drawn with
// `projection`: (w, h, then the camera-space size of a pixel at unit depth,
// across and down), so a shader has a pixel's size at a point as its clip
// w times these, without unprojecting (textures' level of detail).
glm::vec4 viewportOf(const glm::mat4& projection, std::uint32_t w, std::uint32_t h);

// Camera-space depth (distance along the view axis) for a stored depth
// value of projection(); +infinity for 0 (the cleared far value).
float linearDepth(const Camera& camera, float storedDepth);

}  // namespace tsr::vk
