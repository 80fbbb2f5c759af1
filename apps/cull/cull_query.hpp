#pragma once
// A view the culling service ranks objects for, and its answer: plain
// values, apart from the scene they were decoded for or ranked on.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "tsr/sg/types.hpp"

namespace tsr::app {

struct CullQuery {
  glm::vec3 position{0.0f}, target{0.0f, 0.0f, -1.0f}, up{0.0f, 1.0f, 0.0f};
  float fovDegrees = 45.0f;  // vertical
  std::uint32_t width = 0, height = 0;
  std::uint32_t maxObjects = 0;
};

struct CulledObject {
  sg::ContainerId id = sg::kNoContainer;
  std::string name;
  std::uint64_t pixels = 0;
  double fraction = 0;  // of the view's pixels
  std::uint64_t triangles = 0;
};

struct CullAnswer {
  std::vector<CulledObject> objects;  // by pixels, most first; at most maxObjects
  double coveredFraction = 0;         // of the view's pixels, by every object seen
  std::uint64_t totalObjects = 0, totalTriangles = 0;
};

}  // namespace tsr::app
