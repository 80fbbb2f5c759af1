#pragma once

#include <glm/vec3.hpp>

#include <variant>

namespace tsr::vk {

// Units are those of the Embree back-end so both render the same direct light.
// Intensity in W/sr, per colour channel. Point lights cast no shadows.
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
  bool castShadows = true;  // shadow map, if the renderer has shadows on
};

// Light arriving from infinitely far along `direction` (the direction the
// light travels); irradiance in W/m^2 on a surface facing it.
struct DirectionalLight {
  glm::vec3 direction{0.0f, -1.0f, 0.0f};
  glm::vec3 irradiance{1.0f};
  bool castShadows = true;
};

using Light = std::variant<PointLight, SpotLight, DirectionalLight>;

}  // namespace tsr::vk
