#pragma once

#include "culling/depth_pyramid.hpp"
#include "resources/buffer.hpp"
#include "resources/command_slot.hpp"
#include "resources/compute_pipeline.hpp"
#include "scene/scene_state.hpp"

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <optional>
#include <span>

namespace tsr::vk {

// Two-phase occlusion culling for one renderer (one viewport, tile or eye),
// after zeux's niagara: the early phase draws what was visible last frame;
// its depth becomes a pyramid; the late phase tests every object's bounds
// against it and draws the visible ones not drawn yet. Unlike niagara, the
// finished frame's depth is tested once more for the next early phase: the
// late test against a sparse early depth passes many hidden objects (all of
// them on a first frame), which would otherwise be drawn early next frame.
//
// Draw commands are indexed by position in the renderer's draw order (one
// per opaque instance, instanceCount 0 or 1, firstInstance = position), so
// the surviving draws run in the full draw's order: with a still camera the
// image is the full draw's, bit for bit. Visibility is kept per instance
// slot; a slot the culler has not seen starts invisible (tested late).
class OcclusionCuller {
 public:
  explicit OcclusionCuller(const Device& device);

  // Writes the per-position records (slot, index count, mesh bounds) for
  // the opaque draw order. Forgets visibility when the scene is another one.
  void prepare(const SceneState& s, std::span<const std::uint32_t> opaqueOrder);
  // Early commands: last frame's visible objects inside the frustum. The
  // pyramid must be sized (DepthPyramid::ensure) first.
  void recordEarly(VkCommandBuffer cmd, const SceneState& s, const glm::mat4& viewProj, const DepthPyramid& pyramid,
                   std::uint32_t width, std::uint32_t height);
  // Late commands, from the pyramid of the early draws.
  void recordLate(VkCommandBuffer cmd, const glm::mat4& viewProj, std::uint32_t width, std::uint32_t height);
  // Next frame's visibility, from the pyramid of the finished frame.
  void recordVisibility(VkCommandBuffer cmd, const glm::mat4& viewProj, std::uint32_t width, std::uint32_t height);

  VkBuffer earlyCommands() const { return early_.handle(); }
  VkBuffer lateCommands() const { return late_.handle(); }

  struct Drawn {
    std::uint64_t earlyTriangles = 0, lateTriangles = 0;
    std::uint32_t earlyObjects = 0, lateObjects = 0;
  };
  // What the last recorded frame drew; read after it completed.
  Drawn drawn() const;

 private:
  void dispatch(VkCommandBuffer cmd, const glm::mat4& viewProj, std::uint32_t phase, std::uint32_t width,
                std::uint32_t height);

  const Device& device_;
  ComputePipeline cull_;
  DescriptorSlot descriptors_;
  Buffer records_;
  Buffer visibility_;
  Buffer early_;
  Buffer late_;
  std::uint32_t count_ = 0;
  std::size_t slots_ = 0;
  const SceneState* scene_ = nullptr;
};

}  // namespace tsr::vk
