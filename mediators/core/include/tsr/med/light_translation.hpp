#pragma once
// A scene-graph light in the back-ends' shared vocabulary
// (backends/common): written once for every back-end, so they all light a
// scene with the same lights.
#include <glm/mat4x4.hpp>

#include "tsr/backend/light.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::med {

// The light placed by its world matrix: position and direction moved by it
// (the direction normalised), power = colour x intensity.
backend::Light translateLight(const sg::Light& light, const glm::mat4& world);

}  // namespace tsr::med
