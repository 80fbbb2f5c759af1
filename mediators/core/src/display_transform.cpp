#include "tsr/med/display_transform.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tsr::med {

namespace {
float acesFitted(float x) {
  x = std::max(x, 0.0f);
  return std::clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
}
}  // namespace

glm::vec4 DisplayTransform::apply(const glm::vec4& radiance) const {
  const float scale = std::exp2(exposureEv);
  glm::vec4 out = radiance;
  for (int c = 0; c < 3; ++c) {
    out[c] *= scale;
    if (curve == ToneCurve::Filmic) out[c] = acesFitted(out[c]);
  }
  return out;
}

ToneCurve parseToneCurve(const std::string& name) {
  if (name == "none") return ToneCurve::None;
  if (name == "filmic") return ToneCurve::Filmic;
  throw std::invalid_argument("--tonemap " + name + ": expected none or filmic");
}

}  // namespace tsr::med
