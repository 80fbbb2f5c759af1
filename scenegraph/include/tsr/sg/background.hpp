#pragma once
// What camera rays that hit nothing see: a colour, a vertical gradient or
// an environment map (latitude-longitude), scaled by an intensity; and
// the medium that fills the scene outside every volume (fog), if any.
#include "tsr/sg/container_of.hpp"

namespace tsr::sg {

enum class BackgroundKind : std::uint8_t { Color, Gradient, Environment, Count };

class Background final : public ContainerOf<Background, ContainerType::Background> {
 public:
  enum Field : FieldIndex { Kind = kFirstOwnField, Color, GradientTop, GradientBottom, Environment, Intensity, Medium };

  BackgroundKind kind() const { return kind_; }
  const Vec3& color() const { return color_; }
  const Vec3& gradientTop() const { return top_; }
  const Vec3& gradientBottom() const { return bottom_; }
  ContainerId environment() const { return environment_; }
  float intensity() const { return intensity_; }
  ContainerId medium() const { return medium_; }  // a VolumeMaterial (its textures unused), or none

  void setKind(BackgroundKind k) { set<&Background::kind_>(k); }
  void setColor(const Vec3& v) { set<&Background::color_>(v); }
  void setGradient(const Vec3& top, const Vec3& bottom) {
    set<&Background::top_>(top);
    set<&Background::bottom_>(bottom);
  }
  void setEnvironment(ContainerId image) { set<&Background::environment_>(image); }
  void setIntensity(float v) { set<&Background::intensity_>(v); }
  void setMedium(ContainerId v) { set<&Background::medium_>(v); }

  static constexpr auto fieldSpecs() {
    using M = Background;
    // The gradient's ends change together, through setGradient.
    constexpr auto kSetTop = +[](M& b, const Vec3& v) { b.setGradient(v, b.gradientBottom()); };
    constexpr auto kSetBottom = +[](M& b, const Vec3& v) { b.setGradient(b.gradientTop(), v); };
    return std::tuple{valueField(Kind, "kind", &M::kind_, &M::setKind),
                      valueField(Color, "color", &M::color_, &M::setColor),
                      valueField(GradientTop, "gradientTop", &M::top_, kSetTop),
                      valueField(GradientBottom, "gradientBottom", &M::bottom_, kSetBottom),
                      referenceField(Environment, "environment", &M::environment_, kImageTypes, &M::setEnvironment),
                      valueField(Intensity, "intensity", &M::intensity_, &M::setIntensity),
                      referenceField(Medium, "medium", &M::medium_, kVolumeTypes, &M::setMedium)};
  }

 private:
  BackgroundKind kind_ = BackgroundKind::Color;
  Vec3 color_{0.0f};
  Vec3 top_{0.5f, 0.7f, 1.0f};
  Vec3 bottom_{1.0f};
  ContainerId environment_ = kNoContainer;
  float intensity_ = 1.0f;
  ContainerId medium_ = kNoContainer;
};

}  // namespace tsr::sg
