#pragma once
// The point, spot and directional lights evaluated: what arrives at a point
// from one of them (the path tracer's direct light) and a spot light's
// falloff (which the photon pass also applies to the photons it emits).
// The one place that says how these lights shine. Private to the back-end.
#include "tsr/embree/vocabulary.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <cmath>
#include <limits>
#include <optional>
#include <variant>

namespace tsr::embree {

// A spot light's share of its intensity at cosAngle off its axis: all of it
// inside the inner cone, none outside the outer one, smooth in between.
inline float spotFalloff(const SpotLight& light, float cosAngle) {
  const float cosOuter = std::cos(light.outerAngle), cosInner = std::cos(light.innerAngle);
  return cosAngle >= cosInner ? 1.0f : cosAngle <= cosOuter ? 0.0f : glm::smoothstep(cosOuter, cosInner, cosAngle);
}

// Light from a delta light at a point: the direction towards the light, the
// irradiance it gives a surface facing it, and how far a shadow ray goes.
struct LightArrival {
  glm::vec3 wi{0.0f};
  glm::vec3 li{0.0f};
  float tfar = std::numeric_limits<float>::infinity();
};

// Where a point or spot light stands; nothing for a directional light.
inline std::optional<glm::vec3> lightPosition(const Light& light) {
  if (const auto* sl = std::get_if<SpotLight>(&light)) return sl->position;
  if (const auto* pl = std::get_if<PointLight>(&light)) return pl->position;
  return std::nullopt;
}

// False when nothing arrives: the point is at the light's position, or
// outside a spot light's cone.
inline bool lightArriving(const Light& light, const glm::vec3& p, LightArrival& out) {
  if (const auto* dl = std::get_if<DirectionalLight>(&light)) {
    out.wi = -glm::normalize(dl->direction);
    out.li = dl->irradiance;
    return true;
  }
  const auto* sl = std::get_if<SpotLight>(&light);
  const glm::vec3 d = (sl ? sl->position : std::get<PointLight>(light).position) - p;
  const float d2 = glm::dot(d, d);
  if (!(d2 > 0.0f)) return false;
  const float dist = std::sqrt(d2);
  out.wi = d / dist;
  out.tfar = dist * (1.0f - 1e-4f);
  if (!sl) {
    out.li = std::get<PointLight>(light).intensity / d2;
    return true;
  }
  const float falloff = spotFalloff(*sl, glm::dot(glm::normalize(sl->direction), -out.wi));
  if (falloff <= 0.0f) return false;
  out.li = sl->intensity * (falloff / d2);
  return true;
}

}  // namespace tsr::embree
