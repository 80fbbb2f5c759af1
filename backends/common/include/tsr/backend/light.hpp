#pragma once

#include <glm/vec3.hpp>

#include <variant>

namespace tsr::backend {

// Punctual lights in one set of units, so every back-end renders the same
// direct light. castShadows is the rasterizer's (a shadow map, if its
// shadows are on; its point lights cast none); the path tracer always
// traces shadow rays.

// Intensity in W/sr (radiance units times area), per colour channel.
struct PointLight {
  glm::vec3 position{0.0f};
  glm::vec3 intensity{1.0f};
};

// A point light restricted to a cone; full intensity inside innerAngle,
// smoothstep falloff to zero at outerAngle (half-angles in radians).
struct SpotLight {
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};
  glm::vec3 intensity{1.0f};
  float innerAngle = 0.3f;
  float outerAngle = 0.4f;
  bool castShadows = true;
};

// Light arriving from infinitely far along `direction` (the direction the
// light travels); irradiance in W/m^2 on a surface facing it.
struct DirectionalLight {
  glm::vec3 direction{0.0f, -1.0f, 0.0f};
  glm::vec3 irradiance{1.0f};
  bool castShadows = true;
};

using Light = std::variant<PointLight, SpotLight, DirectionalLight>;

}  // namespace tsr::backend
