#pragma once
// Scenes made in code, for tests, demos and benchmarks without files.
#include <string>

#include "parsed_scene.hpp"

namespace tsr::sg::builtin {

// The Cornell box of make_cornell.py, lit by an emissive ceiling quad, with
// a mirror sphere on the tall block and a glass sphere on the short one.
parsed::Scene cornell();
// `count` instances of a few shared meshes on a grid, a camera that sees
// them all and a directional light.
parsed::Scene instances(std::uint64_t count);
// The Cornell box with a cube sliding across the floor and a point light
// circling under the ceiling, as one looping 4-second animation.
parsed::Scene animated();

}  // namespace tsr::sg::builtin
