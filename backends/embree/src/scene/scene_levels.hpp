#pragma once
// Where each instance is traced from (Level: the merged scene, the top
// level, the moving level, or a ghost in the top level with its copy in the
// moving level) and the commit steps that keep the levels and the meshes'
// own BVHs up to date with the edits of SceneState::pending.

#include "scene/scene_state.hpp"

#include <glm/mat4x4.hpp>

#include <cstdint>

namespace tsr::embree {

// A mesh's triangles in world space (positions copied, indices shared), as
// the merged scene holds them.
RTCGeometry worldGeometry(RTCDevice device, const MeshData& d, const glm::mat4& transform);

// Takes the instance out of whatever level holds it.
void unplace(SceneState& s, InstanceRecord& inst, std::uint32_t id);

// Commit steps 1-3: the changed meshes' BVHs, each changed instance into its
// level, and the levels that changed.
void commitLevels(SceneState& s);

}  // namespace tsr::embree
