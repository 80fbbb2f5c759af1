#include "scene/volume_field.hpp"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

namespace tsr::embree {

namespace {

// The largest value of each colour channel, not below zero: trilinear
// interpolation never exceeds it, so it bounds the texture everywhere.
glm::vec3 largestTexel(const Texture* t) {
  glm::vec3 m(0.0f);
  if (!t) return glm::vec3(1.0f);
  for (const glm::vec4& v : t->texels()) m = glm::max(m, glm::vec3(v));
  return m;
}

// Position between texel centres along an axis of n texels, clamped to the
// edge texels: the first index and the weight of the next.
struct Lerp {
  std::uint32_t i0, i1;
  float t;
};
Lerp axis(float u, std::uint32_t n) {
  const float f = std::clamp(u * float(n) - 0.5f, 0.0f, float(n - 1));
  const auto i0 = std::uint32_t(f);
  return {i0, std::min(i0 + 1, n - 1), f - float(i0)};
}

}  // namespace

VolumeField::VolumeField(const Medium& medium, const Texture* absorption, const Texture* scattering,
                         const Texture* emission)
    : absorption_(absorption), scattering_(scattering), emission_(emission), active_(true) {
  const Texture* any = absorption ? absorption : scattering ? scattering : emission;
  slices_ = std::clamp<std::uint32_t>(medium.textureSlices, 1, any ? any->height() : 1);
  const glm::vec3 sigma = glm::max(medium.absorption, 0.0f) * largestTexel(absorption) +
                          glm::max(medium.scattering, 0.0f) * largestTexel(scattering);
  majorant_ = std::max({sigma.x, sigma.y, sigma.z});
}

glm::vec3 VolumeField::sample(const Texture* t, const glm::vec3& unit) const {
  if (!t) return glm::vec3(1.0f);
  const std::uint32_t sliceHeight = std::max<std::uint32_t>(t->height() / slices_, 1);
  const std::uint32_t slices = std::min(slices_, t->height());
  // A slice is a picture of the box's cross-section seen from +z: its
  // left column at the lowest x, its top row at the highest y.
  const Lerp x = axis(unit.x, t->width()), y = axis(1.0f - unit.y, sliceHeight), z = axis(unit.z, slices);
  auto row = [&](std::uint32_t yi, std::uint32_t zi) {
    const std::uint32_t r = zi * sliceHeight + yi;
    return glm::mix(glm::vec3(t->texel(x.i0, r)), glm::vec3(t->texel(x.i1, r)), x.t);
  };
  auto slice = [&](std::uint32_t zi) { return glm::mix(row(y.i0, zi), row(y.i1, zi), y.t); };
  return glm::max(glm::mix(slice(z.i0), slice(z.i1), z.t), 0.0f);
}

MediumCoefficients VolumeField::at(const Medium& m, const glm::vec3& unit) const {
  return {glm::max(m.absorption, 0.0f) * sample(absorption_, unit),
          glm::max(m.scattering, 0.0f) * sample(scattering_, unit), m.emission * sample(emission_, unit)};
}

}  // namespace tsr::embree
