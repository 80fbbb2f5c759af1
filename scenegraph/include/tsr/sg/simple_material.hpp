#pragma once
// The OpenGL 1.1-style material every back-end understands.
#include "tsr/sg/container_of.hpp"

namespace tsr::sg {

class SimpleMaterial final : public ContainerOf<SimpleMaterial, ContainerType::SimpleMaterial> {
 public:
  enum Field : FieldIndex { Diffuse = kFirstOwnField, DiffuseTexture, Specular, Shininess, Emission, Transparency };

  const Vec3& diffuse() const { return diffuse_; }
  ContainerId diffuseTexture() const { return diffuseTexture_; }
  const Vec3& specular() const { return specular_; }
  float shininess() const { return shininess_; }
  const Vec3& emission() const { return emission_; }
  float transparency() const { return transparency_; }  // 0 opaque, 1 invisible

  void setDiffuse(const Vec3& v) { set<&SimpleMaterial::diffuse_>(v); }
  void setDiffuseTexture(ContainerId image) { set<&SimpleMaterial::diffuseTexture_>(image); }
  void setSpecular(const Vec3& v) { set<&SimpleMaterial::specular_>(v); }
  void setShininess(float v) { set<&SimpleMaterial::shininess_>(v); }
  void setEmission(const Vec3& v) { set<&SimpleMaterial::emission_>(v); }
  void setTransparency(float v) { set<&SimpleMaterial::transparency_>(v); }

  static constexpr auto fieldSpecs() {
    using M = SimpleMaterial;
    return std::tuple{
        valueField(Diffuse, "diffuse", &M::diffuse_, &M::setDiffuse),
        referenceField(DiffuseTexture, "diffuseTexture", &M::diffuseTexture_, kImageTypes, &M::setDiffuseTexture),
        valueField(Specular, "specular", &M::specular_, &M::setSpecular),
        valueField(Shininess, "shininess", &M::shininess_, &M::setShininess),
        valueField(Emission, "emission", &M::emission_, &M::setEmission),
        valueField(Transparency, "transparency", &M::transparency_, &M::setTransparency)};
  }

 private:
  Vec3 diffuse_{0.8f};
  ContainerId diffuseTexture_ = kNoContainer;
  Vec3 specular_{0.0f};
  float shininess_ = 32.0f;
  Vec3 emission_{0.0f};
  float transparency_ = 0.0f;
};

}  // namespace tsr::sg
