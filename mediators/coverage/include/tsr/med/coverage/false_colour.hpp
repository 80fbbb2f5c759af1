#pragma once
// A stable colour per object id for looking at id images: bright enough
// to stand out from the black background, hashed so neighbours differ.
#include <glm/vec3.hpp>

#include "tsr/sg/types.hpp"

namespace tsr::med {

glm::vec3 falseColour(sg::ContainerId id);  // black for kNoContainer

}  // namespace tsr::med
