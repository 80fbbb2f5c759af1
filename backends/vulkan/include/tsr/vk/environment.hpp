#pragma once

#include "tsr/vk/medium.hpp"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <optional>
#include <span>

namespace tsr::vk {

// What the rasterizer keeps of the environment: its average radiance, which
// lights every surface as an unshadowed ambient term (a constant environment
// is exact for Lambertian surfaces without occlusion), and the fog, if any.
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

  const glm::vec3& averageRadiance() const { return average_; }
  bool isBlack() const { return average_ == glm::vec3(0.0f); }
  const std::optional<Medium>& fog() const { return fog_; }

 private:
  glm::vec3 average_{0.0f};
  std::optional<Medium> fog_;
};

}  // namespace tsr::vk
