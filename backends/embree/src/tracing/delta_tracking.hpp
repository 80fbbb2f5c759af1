#pragma once
// Heterogeneous (textured) media, traced against a majorant: tentative
// collisions at the majorant's rate, each of which is real or null by the
// coefficients there (Woodcock's delta tracking for free flights, ratio
// tracking for the transmittance of shadow rays; Novák et al. 2014, as
// pbrt-v4 does). The majorant is grey; colour channels stay unbiased by
// choosing each event by the mean of the channels' coefficients and
// weighting by the channel's own over it (spectral tracking, Kutz 2017).
#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "scene/volume_field.hpp"
#include "tracing/media.hpp"

namespace tsr::embree {

// A ray inside a textured medium: world-space distance t along it maps to
// a point of the field's unit cube.
class FieldRay {
 public:
  FieldRay(const MediumAt& m, const glm::vec3& org, const glm::vec3& dir)
      : medium_(*m.medium),
        field_(*m.field()),
        org_(glm::vec3(m.instance->worldToVolume * glm::vec4(org, 1.0f))),
        dir_(glm::mat3(m.instance->worldToVolume) * dir) {}

  float majorant() const { return field_.majorant(); }
  MediumCoefficients at(float t) const { return field_.at(medium_, org_ + t * dir_); }
  const Medium& medium() const { return medium_; }

 private:
  const Medium& medium_;
  const VolumeField& field_;
  glm::vec3 org_, dir_;
};

// A runaway walk (a majorant far above the texels) ends unresolved.
inline constexpr int kMaxTentativeCollisions = 1 << 16;

inline float channelMean(const glm::vec3& v) { return (v.x + v.y + v.z) / 3.0f; }

// Where a flight ends before tMax, scoring the medium's emission at each
// tentative collision (emit(radiance), already weighted). At a real
// scattering event `scattered` is set; an absorption ends the path with
// weight 0; reaching tMax keeps the weight the null collisions gave.
template <class Random, class Emit>
FreeFlight deltaTrack(const FieldRay& ray, float tMax, Random&& uniform, Emit&& emit) {
  FreeFlight f;
  const float majorant = ray.majorant();
  if (!(majorant > 0.0f)) {  // nothing collides: emission by one point of the segment
    const float u = uniform();
    if (std::isfinite(tMax)) emit(ray.at(u * tMax).emission * tMax);
    f.t = tMax;
    return f;
  }
  float t = 0.0f;
  for (int i = 0; i < kMaxTentativeCollisions; ++i) {
    t -= std::log1p(-uniform()) / majorant;
    if (t >= tMax) {
      f.t = tMax;
      return f;
    }
    const MediumCoefficients c = ray.at(t);
    emit(f.weight * c.emission / majorant);
    const glm::vec3 null = glm::max(glm::vec3(majorant) - c.extinction(), 0.0f);
    const float pa = channelMean(c.absorption), ps = channelMean(c.scattering), pn = channelMean(null);
    const float total = pa + ps + pn;
    const float u = uniform() * total;
    if (u < pa) {
      f.weight = glm::vec3(0.0f);
      f.t = t;
      return f;
    }
    if (u < pa + ps) {
      f.weight *= c.scattering * (total / (majorant * ps));
      f.scattered = true;
      f.t = t;
      return f;
    }
    f.weight *= null * (total / (majorant * pn));
  }
  f.weight = glm::vec3(0.0f);
  f.t = t;
  return f;
}

// What passes the first tMax of the ray: the product of the null
// probabilities at tentative collisions (ratio tracking), with Russian
// roulette once little is left.
template <class Random>
glm::vec3 ratioTrack(const FieldRay& ray, float tMax, Random&& uniform) {
  const float majorant = ray.majorant();
  glm::vec3 passed(1.0f);
  if (!(majorant > 0.0f)) return passed;
  float t = 0.0f;
  for (int i = 0; i < kMaxTentativeCollisions; ++i) {
    t -= std::log1p(-uniform()) / majorant;
    if (t >= tMax) return passed;
    passed *= glm::max(1.0f - ray.at(t).extinction() / majorant, 0.0f);
    const float left = std::max({passed.x, passed.y, passed.z});
    if (left < 0.1f) {
      if (left <= 0.0f || uniform() >= 0.5f) return glm::vec3(0.0f);
      passed *= 2.0f;
    }
  }
  return glm::vec3(0.0f);
}

}  // namespace tsr::embree
