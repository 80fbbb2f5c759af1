#pragma once

#include "tsr/vk/medium.hpp"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace tsr::vk {

// What the rasterizer keeps of the environment: its average radiance, which
// lights every surface as an unshadowed ambient term (a constant environment
// is exact for Lambertian surfaces without occlusion); the radiance
// prefiltered by GGX roughness, which specular surfaces reflect (split-sum
// image-based lighting); and the fog, if any. Prefiltering happens here,
// once per environment, never per frame.
class Environment {
 public:
  Environment() = default;  // black
  static Environment constant(const glm::vec3& radiance);
  // Lat-long (equirectangular) radiance map, row 0 = straight up; the average
  // is weighted by each row's solid angle.
  static Environment latLong(std::uint32_t width, std::uint32_t height, std::span<const glm::vec4> texels,
                             float scale = 1.0f);

  // The medium filling the scene outside every volume (fog); none if empty.
  Environment withFog(const Medium& fog) const;

  // kLevels lat-long images of kWidth x kHeight stacked vertically, level k
  // for GGX roughness k / (kLevels - 1) (level 0: the map itself), in the
  // path tracer's convention: u = atan2(x, -z) / 2pi + 1/2, v = acos(y) / pi.
  static constexpr std::uint32_t kWidth = 64, kHeight = 32, kLevels = 5;
  const std::vector<glm::vec4>& prefiltered() const { return prefiltered_; }

  // Radiance from direction d (towards the environment), from level 0.
  glm::vec3 radiance(const glm::vec3& d) const;
  const glm::vec3& averageRadiance() const { return average_; }
  bool isBlack() const { return average_ == glm::vec3(0.0f); }
  const std::optional<Medium>& fog() const { return fog_; }

 private:
  glm::vec3 average_{0.0f};
  std::optional<Medium> fog_;
  std::vector<glm::vec4> prefiltered_ = std::vector<glm::vec4>(kWidth * kHeight * kLevels, glm::vec4(0.0f));
};

}  // namespace tsr::vk
