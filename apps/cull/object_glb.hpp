#pragma once
// One object of a scene as a standalone glTF binary: each of its geometry
// instances as a mesh in world space (positions, normals, indices) with
// its material's base colour, metallic and roughness, for a web client
// that loads objects one by one.
#include <cstdint>
#include <vector>

#include "tsr/med/scene_flattening.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::app {

std::vector<std::uint8_t> objectGlb(const sg::Scene& scene, const std::vector<med::FlatNode>& instances);

}  // namespace tsr::app
