#pragma once
// Geometry instances of a scene as a standalone glTF binary: each a mesh in
// world space (positions, normals, indices) with its material's base
// colour, metallic, roughness, emission (with its strength), transmission
// and ior, and the given cameras in world space. One object for a web client
// that loads objects one by one (tessera-cull), or a whole scene
// (tessera-inspect --write-glb, e.g. a built-in scene for other tools).
// A scene whose unit is not the metre (builtin:cornell's millimetres) sits
// under one root node scaled by metresPerUnit, so other tools see its size.
#include <cstdint>
#include <vector>

#include "tsr/med/scene_flattening.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::app {

std::vector<std::uint8_t> glbOf(const sg::Scene& scene, const std::vector<med::FlatNode>& instances,
                                const std::vector<sg::ContainerId>& cameras = {}, float metresPerUnit = 1.0f);

}  // namespace tsr::app
