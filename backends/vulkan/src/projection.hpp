#pragma once
// The shared camera in Vulkan's clip space: the off-axis projection of a
// region's sub-window with reversed depth, and the way back from depth.
#include <glm/mat4x4.hpp>

#include "tsr/vk/vocabulary.hpp"

namespace tsr::vk {

// Vulkan clip-space projection of the sub-window that `region` cuts out of
// the full image (off-axis), with reversed depth: near -> 1, far -> 0.
glm::mat4 projection(const Camera& camera, const Region& region);

// Camera-space depth (distance along the view axis) for a stored depth
// value of projection(); +infinity for 0 (the cleared far value).
float linearDepth(const Camera& camera, float storedDepth);

}  // namespace tsr::vk
