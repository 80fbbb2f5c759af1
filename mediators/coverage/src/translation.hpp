#pragma once
// Scene graph values in the id pass's vocabulary: meshes, transparency and
// the object id an instance reports. Pure functions; the adapter decides
// when to call them.
#include "tsr/cov/mesh.hpp"
#include "tsr/med/coverage/ranking.hpp"
#include "tsr/med/primitive_of.hpp"
#include "tsr/med/scene_flattening.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::med::coverage_mediator {

// Positions and indices only; animated geometry gets a refittable mesh.
cov::MeshData translateMesh(const sg::Geometry& geometry);

// The rule in register.hpp; no material is opaque.
bool isTransparent(const sg::Container* material);

}  // namespace tsr::med::coverage_mediator
