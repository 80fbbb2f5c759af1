#include "tsr/med/light_translation.hpp"

#include <glm/glm.hpp>

namespace tsr::med {

backend::Light translateLight(const sg::Light& light, const glm::mat4& world) {
  const glm::vec3 position(world * glm::vec4(light.position(), 1.0f));
  const glm::vec3 direction = glm::normalize(glm::vec3(world * glm::vec4(light.direction(), 0.0f)));
  const glm::vec3 power = light.color() * light.intensity();
  switch (light.kind()) {
    case sg::LightKind::Spot:
      return backend::SpotLight{position, direction, power, light.innerConeAngle(), light.outerConeAngle()};
    case sg::LightKind::Directional:
      return backend::DirectionalLight{direction, power};
    default:
      return backend::PointLight{position, power};
  }
}

}  // namespace tsr::med
