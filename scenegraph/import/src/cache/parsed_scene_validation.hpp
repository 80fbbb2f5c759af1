#pragma once
// What buildScene relies on in a parsed::Scene, checked: every reference in
// range, array sizes that agree, finite numbers, a node forest (no cycles,
// no node under two parents), animation keys that match their times. The
// glTF path ensures these while converting; a scene from anywhere else
// (the converted-scene cache) is checked with this before it is built.
#include "parsed_scene.hpp"

namespace tsr::sg::parsed {

// Throws std::runtime_error naming the first problem.
void validateScene(const Scene& scene);

}  // namespace tsr::sg::parsed
