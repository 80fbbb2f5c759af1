#pragma once
// What camera rays that hit nothing see: a colour, a vertical gradient or
// an environment map (latitude-longitude), scaled by an intensity.
#include "tsr/sg/container_of.hpp"

namespace tsr::sg {

enum class BackgroundKind : std::uint8_t { Color, Gradient, Environment, Count };

class Background final : public ContainerOf<Background, ContainerType::Background> {
 public:
  enum Field : FieldIndex { Kind = kFirstOwnField, Color, GradientTop, GradientBottom, Environment, Intensity };

  BackgroundKind kind() const { return kind_; }
  const Vec3& color() const { return color_; }
  const Vec3& gradientTop() const { return top_; }
  const Vec3& gradientBottom() const { return bottom_; }
  ContainerId environment() const { return environment_; }
  float intensity() const { return intensity_; }

  void setKind(BackgroundKind k) { assign(Kind, kind_, k); }
  void setColor(const Vec3& v) { assign(Color, color_, v); }
  void setGradient(const Vec3& top, const Vec3& bottom) {
    assign(GradientTop, top_, top);
    assign(GradientBottom, bottom_, bottom);
  }
  void setEnvironment(ContainerId image) { assignReference(Environment, environment_, image); }
  void setIntensity(float v) { assign(Intensity, intensity_, v); }

  static constexpr auto fieldSpecs() {
    return std::tuple{valueField("kind", &Background::kind_),
                      valueField("color", &Background::color_),
                      valueField("gradientTop", &Background::top_),
                      valueField("gradientBottom", &Background::bottom_),
                      referenceField("environment", &Background::environment_, kImageTypes),
                      valueField("intensity", &Background::intensity_)};
  }

 private:
  BackgroundKind kind_ = BackgroundKind::Color;
  Vec3 color_{0.0f};
  Vec3 top_{0.5f, 0.7f, 1.0f};
  Vec3 bottom_{1.0f};
  ContainerId environment_ = kNoContainer;
  float intensity_ = 1.0f;
};

}  // namespace tsr::sg
