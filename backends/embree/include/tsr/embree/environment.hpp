#pragma once

#include "tsr/embree/medium.hpp"
#include "tsr/embree/texture.hpp"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <memory>
#include <optional>

namespace tsr::embree {

// What a ray that leaves the scene sees: black, a constant colour, or a
// lat-long (equirectangular) radiance map that is importance sampled.
// Map convention: v = 0 is straight up (+Y); u = 0.5 looks along -Z and u
// grows towards +X.
class Environment {
 public:
  Environment();  // black
  static Environment constant(const glm::vec3& radiance);
  static Environment latLong(const Texture& map, float scale = 1.0f);

  bool isBlack() const;
  glm::vec3 radiance(const glm::vec3& direction) const;

  struct Sample {
    glm::vec3 direction{0.0f};
    glm::vec3 radiance{0.0f};
    float pdf = 0.0f;  // solid angle
  };
  Sample sample(const glm::vec2& u) const;
  float pdf(const glm::vec3& direction) const;

  // The medium filling the scene outside every closed volume (fog), if any.
  const std::optional<Medium>& medium() const { return medium_; }
  Environment withMedium(std::optional<Medium> medium) const {
    Environment e = *this;
    e.medium_ = medium && !medium->empty() ? medium : std::nullopt;
    return e;
  }

  static glm::vec2 directionToUv(const glm::vec3& d);
  static glm::vec3 uvToDirection(const glm::vec2& uv);

 private:
  struct Impl;
  std::shared_ptr<const Impl> impl_;
  std::optional<Medium> medium_;
};

}  // namespace tsr::embree
