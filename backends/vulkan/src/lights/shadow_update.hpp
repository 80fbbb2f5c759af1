#pragma once
// What an edit changes in the shadow maps. The maps do not depend on the
// camera; when only instances changed since they were drawn (moved, added,
// removed, given another material) and the lights' projections are the
// same, only the texels under those instances' old and new footprints can
// change: those rectangles are cleared and drawn again from the casters
// that overlap them, and each texel ends with the nearest depth of every
// caster over it, as a full redraw gives it (the depth test keeps the
// minimum whatever the order).
#include "scene/scene_state.hpp"

#include <vulkan/vulkan.h>
#include <glm/mat4x4.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace tsr::vk {

// One instance as the shadow maps were drawn with it.
struct ShadowCaster {
  glm::mat4 transform{1.0f};
  std::uint32_t mesh = 0;
  std::uint32_t material = 0;
  bool alive = false;
  bool operator==(const ShadowCaster&) const = default;
};

// What the shadow maps hold: the scene, its edits other than single
// instances' (mesh vertices, materials), the lights' projections and the
// instances.
struct ShadowContents {
  std::uint64_t scene = 0;    // SceneState::uid
  std::uint64_t version = 0;  // every edit
  std::uint64_t casterEdits = 0;
  std::vector<glm::mat4> viewProj;
  std::vector<ShadowCaster> casters;
};

std::vector<ShadowCaster> shadowCasters(const SceneState& s);

// The texels of a size x size map (a rectangle, empty when off the map) that
// the instance's mesh bounds under `transform` may cover through viewProj,
// a texel of margin around; the whole map when the bounds reach behind a
// spot light's eye.
VkRect2D shadowFootprint(const SceneState& s, std::uint32_t mesh, const glm::mat4& transform, const glm::mat4& viewProj,
                         std::uint32_t size);

// Per shadow layer, the rectangle to draw again from `held` to `now` (empty
// when nothing there changed); nothing when the maps must be drawn whole.
std::optional<std::vector<VkRect2D>> shadowRedraw(const ShadowContents& held, const ShadowContents& now,
                                                  const SceneState& s, std::uint32_t size);

bool overlaps(const VkRect2D& a, const VkRect2D& b);

}  // namespace tsr::vk
