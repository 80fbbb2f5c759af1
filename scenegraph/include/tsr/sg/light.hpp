#pragma once
// A punctual light, placed in the graph under transforms like geometry.
// Position and direction are in the light's local frame (direction is
// where the light shines, default -Z as in glTF).
#include "tsr/sg/container_of.hpp"

namespace tsr::sg {

enum class LightKind : std::uint8_t { Point, Spot, Directional, Count };

class Light final : public ContainerOf<Light, ContainerType::Light> {
 public:
  enum Field : FieldIndex { Kind = kFirstOwnField, Color, Intensity, Position, Direction, InnerCone, OuterCone };

  LightKind kind() const { return kind_; }
  const Vec3& color() const { return color_; }
  // Point and spot: candela-like (radiant intensity, W/sr); directional:
  // irradiance (W/m^2) — as glTF's KHR_lights_punctual, without photometry.
  float intensity() const { return intensity_; }
  const Vec3& position() const { return position_; }
  const Vec3& direction() const { return direction_; }
  float innerConeAngle() const { return innerCone_; }  // radians
  float outerConeAngle() const { return outerCone_; }  // radians

  void setKind(LightKind k) { set<&Light::kind_>(k); }
  void setColor(const Vec3& v) { set<&Light::color_>(v); }
  void setIntensity(float v) { set<&Light::intensity_>(v); }
  void setPosition(const Vec3& v) { set<&Light::position_>(v); }
  void setDirection(const Vec3& v) { set<&Light::direction_>(v); }
  void setInnerConeAngle(float v) { set<&Light::innerCone_>(v); }
  void setOuterConeAngle(float v) { set<&Light::outerCone_>(v); }

  static constexpr auto fieldSpecs() {
    using M = Light;
    return std::tuple{valueField(Kind, "kind", &M::kind_, &M::setKind),
                      valueField(Color, "color", &M::color_, &M::setColor),
                      valueField(Intensity, "intensity", &M::intensity_, &M::setIntensity),
                      valueField(Position, "position", &M::position_, &M::setPosition),
                      valueField(Direction, "direction", &M::direction_, &M::setDirection),
                      valueField(InnerCone, "innerConeAngle", &M::innerCone_, &M::setInnerConeAngle),
                      valueField(OuterCone, "outerConeAngle", &M::outerCone_, &M::setOuterConeAngle)};
  }

 private:
  LightKind kind_ = LightKind::Point;
  Vec3 color_{1.0f};
  float intensity_ = 1.0f;
  Vec3 position_{0.0f};
  Vec3 direction_{0.0f, 0.0f, -1.0f};
  float innerCone_ = 0.0f;
  float outerCone_ = 0.7853982f;
};

}  // namespace tsr::sg
