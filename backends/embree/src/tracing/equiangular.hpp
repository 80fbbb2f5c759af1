#pragma once
// Distances along a ray through a medium sampled towards a point of light:
// density proportional to 1 / (D^2 + (t - delta)^2), D the point's
// distance from the ray's line and delta where it is closest (Kulla &
// Fajardo 2012, "Importance Sampling Techniques for Path Tracing in
// Participating Media", equiangular sampling). Near a small lamp in fog,
// where free-flight distances rarely land, this puts the samples where the
// in-scattered light is. Private to the back-end.
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <numbers>

namespace tsr::embree {

class Equiangular {
 public:
  // The segment [0, tMax) from org along unit dir (tMax may be infinite),
  // towards `light`.
  Equiangular(const glm::vec3& org, const glm::vec3& dir, float tMax, const glm::vec3& light) : tMax_(tMax) {
    delta_ = glm::dot(light - org, dir);
    d_ = glm::length(light - (org + delta_ * dir));
    thetaA_ = std::atan2(-delta_, d_);
    thetaB_ = std::isfinite(tMax) ? std::atan2(tMax - delta_, d_) : 0.5f * std::numbers::pi_v<float>;
    // On the line itself (D ~ 0) the density has no finite normalisation.
    valid_ = d_ > 1e-6f && std::isfinite(delta_) && thetaB_ - thetaA_ > 1e-7f;
  }

  bool valid() const { return valid_; }

  float sample(float u, float* pdf) const {
    const float theta = thetaA_ + u * (thetaB_ - thetaA_);
    const float t = std::min(delta_ + d_ * std::tan(theta), std::nextafter(tMax_, 0.0f));
    *pdf = density(t);
    return std::max(t, 0.0f);
  }

  float density(float t) const {
    if (!valid_ || !(t >= 0.0f && t < tMax_)) return 0.0f;
    const float x = t - delta_;
    return d_ / ((thetaB_ - thetaA_) * (d_ * d_ + x * x));
  }

 private:
  float tMax_;
  float delta_ = 0.0f, d_ = 0.0f, thetaA_ = 0.0f, thetaB_ = 0.0f;
  bool valid_ = false;
};

}  // namespace tsr::embree
