#pragma once
// From linear radiance to what an 8-bit picture shows: an exposure in
// stops, then a tone curve. "filmic" is Narkowicz's fit of the ACES
// reference rendering transform (2015: (x (2.51 x + 0.03)) / (x (2.43 x +
// 0.59) + 0.14), clamped to [0, 1]), which rolls highlights off instead of
// clipping them. Float outputs (EXR) never pass through it.
#include <string>

#include <glm/vec4.hpp>

namespace tsr::med {

enum class ToneCurve { None, Filmic };

struct DisplayTransform {
  float exposureEv = 0.0f;  // radiance x 2^EV
  ToneCurve curve = ToneCurve::None;

  bool identity() const { return exposureEv == 0.0f && curve == ToneCurve::None; }
  // Colour channels only; alpha passes through.
  glm::vec4 apply(const glm::vec4& radiance) const;
};

// "none" or "filmic"; throws std::invalid_argument naming the choices.
ToneCurve parseToneCurve(const std::string& name);

}  // namespace tsr::med
