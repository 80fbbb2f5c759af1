#pragma once
// A punctual light, placed in the graph under transforms like geometry.
// Position and direction are in the light's local frame (direction is
// where the light shines, default -Z as in glTF).
#include "tsr/sg/container_of.hpp"

namespace tsr::sg {

enum class LightKind : std::uint8_t { Point, Spot, Directional, Count };

class Light final : public ContainerOf<Light, ContainerType::Light> {
 public:
  enum Field : FieldIndex { Kind = kFirstOwnField, Color, Intensity, Position, Direction, InnerCone, OuterCone, Range };

  LightKind kind() const { return kind_; }
  const Vec3& color() const { return color_; }
  // Point and spot: candela-like (radiant intensity, W/sr); directional:
  // irradiance (W/m^2) — as glTF's KHR_lights_punctual, without photometry.
  float intensity() const { return intensity_; }
  const Vec3& position() const { return position_; }
  const Vec3& direction() const { return direction_; }
  float innerConeAngle() const { return innerCone_; }  // radians
  float outerConeAngle() const { return outerCone_; }  // radians
  float range() const { return range_; }               // 0: unlimited

  void setKind(LightKind k) { assign(Kind, kind_, k); }
  void setColor(const Vec3& v) { assign(Color, color_, v); }
  void setIntensity(float v) { assign(Intensity, intensity_, v); }
  void setPosition(const Vec3& v) { assign(Position, position_, v); }
  void setDirection(const Vec3& v) { assign(Direction, direction_, v); }
  void setInnerConeAngle(float v) { assign(InnerCone, innerCone_, v); }
  void setOuterConeAngle(float v) { assign(OuterCone, outerCone_, v); }
  void setRange(float v) { assign(Range, range_, v); }

  static constexpr auto fieldSpecs() {
    return std::tuple{valueField("kind", &Light::kind_),
                      valueField("color", &Light::color_),
                      valueField("intensity", &Light::intensity_),
                      valueField("position", &Light::position_),
                      valueField("direction", &Light::direction_),
                      valueField("innerConeAngle", &Light::innerCone_),
                      valueField("outerConeAngle", &Light::outerCone_),
                      valueField("range", &Light::range_)};
  }

 private:
  LightKind kind_ = LightKind::Point;
  Vec3 color_{1.0f};
  float intensity_ = 1.0f;
  Vec3 position_{0.0f};
  Vec3 direction_{0.0f, 0.0f, -1.0f};
  float innerCone_ = 0.0f;
  float outerCone_ = 0.7853982f;
  float range_ = 0.0f;
};

}  // namespace tsr::sg
