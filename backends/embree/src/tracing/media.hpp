#pragma once
// Media along a path: which medium a point is in (a stack of the closed
// volumes the path has entered, over the scene's fog), and, for
// homogeneous media, where a ray's free flight ends, what passes a
// segment, and what a segment emits (textured media: delta_tracking.hpp).
// Colour channels have their own extinction; a distance is sampled in one
// channel picked at random and weighted by the mean of the three channels'
// densities (single-sample MIS over channels, as pbrt-v4's spectral
// tracking does), so chromatic media converge like grey ones.
#include <array>
#include <cmath>
#include <limits>

#include <glm/vec3.hpp>

#include "scene/scene_state.hpp"
#include "tsr/embree/medium.hpp"

namespace tsr::embree {

// A medium along a path: its coefficients and, for a closed mesh's
// interior, the instance whose mesh it fills (a textured interior's
// textures lie over that mesh's bounds).
struct MediumAt {
  const Medium* medium = nullptr;
  const InstanceView* instance = nullptr;

  explicit operator bool() const { return medium != nullptr; }
  const VolumeField* field() const {
    return instance && instance->material->interior.active() ? &instance->material->interior : nullptr;
  }
};

class MediumStack {
 public:
  explicit MediumStack(const Medium* outside = nullptr) : outside_{outside, nullptr} {}
  MediumAt current() const { return size_ ? items_[size_ - 1] : outside_; }
  // Crossing a boundary of `inside`: entering when the ray goes against
  // the face normal. Leaving drops the instance's own entry, or else the
  // latest entry of the same medium (a path that started inside it). A
  // stack deeper than kDepth forgets the extra entries.
  void cross(const MediumAt& inside, bool entering) {
    if (entering) {
      if (size_ < kDepth) items_[size_++] = inside;
      return;
    }
    int found = -1;
    for (int i = size_ - 1; i >= 0 && found < 0; --i)
      if (items_[i].medium == inside.medium && items_[i].instance == inside.instance) found = i;
    for (int i = size_ - 1; i >= 0 && found < 0; --i)
      if (items_[i].medium == inside.medium) found = i;
    if (found < 0) return;
    for (int j = found; j + 1 < size_; ++j) items_[j] = items_[j + 1];
    --size_;
  }

 private:
  static constexpr int kDepth = 8;
  std::array<MediumAt, kDepth> items_{};
  int size_ = 0;
  MediumAt outside_;
};

// exp(-sigma * t) per channel; a channel without extinction passes
// everything, even over an infinite segment.
inline glm::vec3 transmittance(const glm::vec3& sigma, float t) {
  glm::vec3 out;
  for (int c = 0; c < 3; ++c) out[c] = sigma[c] > 0.0f ? std::exp(-sigma[c] * t) : 1.0f;
  return out;
}

// Radiance a segment of length t emits towards its start: the integral of
// transmittance times emission (e t where nothing absorbs). Nothing for an
// infinite segment that would emit without bound.
inline glm::vec3 segmentEmission(const Medium& m, float t) {
  const glm::vec3 sigma = m.extinction();
  glm::vec3 out;
  for (int c = 0; c < 3; ++c) {
    if (m.emission[c] <= 0.0f) {
      out[c] = 0.0f;
    } else if (sigma[c] > 0.0f) {
      out[c] = m.emission[c] * -std::expm1(-sigma[c] * t) / sigma[c];
    } else {
      out[c] = std::isfinite(t) ? m.emission[c] * t : 0.0f;
    }
  }
  return out;
}

// The density with which a free flight (one channel picked at random,
// then its distance) stops at distance t where the channels' extinction is
// sigma and their transmittance T: the channels' mean of sigma T.
inline float collisionDensity(const glm::vec3& sigma, const glm::vec3& T) {
  return (sigma.x * T.x + sigma.y * T.y + sigma.z * T.z) / 3.0f;
}

struct FreeFlight {
  bool scattered = false;  // a real collision before tMax
  float t = 0.0f;
  glm::vec3 weight{1.0f};  // what the path's throughput is multiplied by
};

// Where a flight through `m` ends before tMax (a surface or infinity):
// at a scattering point (weight T sigma_s / pdf) or at tMax (T / P).
inline FreeFlight sampleFreeFlight(const Medium& m, float tMax, float uChannel, float uDistance) {
  const glm::vec3 sigma = m.extinction();
  const int c = std::min(int(uChannel * 3.0f), 2);
  FreeFlight f;
  f.t = sigma[c] > 0.0f ? -std::log1p(-uDistance) / sigma[c] : std::numeric_limits<float>::infinity();
  if (f.t < tMax) {
    const glm::vec3 T = transmittance(sigma, f.t);
    const float pdf = collisionDensity(sigma, T);
    f.scattered = true;
    f.weight = pdf > 0.0f ? T * m.scattering / pdf : glm::vec3(0.0f);
    return f;
  }
  const glm::vec3 T = transmittance(sigma, tMax);
  const float survive = (T.x + T.y + T.z) / 3.0f;
  f.t = tMax;
  f.weight = survive > 0.0f ? T / survive : glm::vec3(0.0f);
  return f;
}

}  // namespace tsr::embree
