#pragma once
// A portable physically based material in the spirit of X3D's
// CommonSurfaceShader (dissertation appendix 5.A) and glTF's metallic-
// roughness model. Every factor has an optional texture that multiplies it.
#include "tsr/sg/container_of.hpp"

namespace tsr::sg {

class SurfaceMaterial final : public ContainerOf<SurfaceMaterial, ContainerType::SurfaceMaterial> {
 public:
  enum Field : FieldIndex {
    BaseColor = kFirstOwnField,
    BaseColorTexture,
    Opacity,
    Metallic,
    Roughness,
    MetallicRoughnessTexture,
    Specular,
    SpecularTexture,
    Emission,
    EmissionStrength,
    EmissionTexture,
    Transmission,
    TransmissionTexture,
    Ior,
    NormalTexture,
    NormalScale,
  };

  const Vec3& baseColor() const { return baseColor_; }
  ContainerId baseColorTexture() const { return baseColorTexture_; }  // RGB(A), sRGB
  float opacity() const { return opacity_; }                          // alpha coverage, 1 opaque
  float metallic() const { return metallic_; }
  float roughness() const { return roughness_; }
  // glTF convention: roughness in the green channel, metallic in blue.
  ContainerId metallicRoughnessTexture() const { return metallicRoughnessTexture_; }
  float specular() const { return specular_; }  // dielectric specular weight, 1 = physical
  ContainerId specularTexture() const { return specularTexture_; }
  const Vec3& emission() const { return emission_; }
  float emissionStrength() const { return emissionStrength_; }
  ContainerId emissionTexture() const { return emissionTexture_; }
  Vec3 emittedRadiance() const { return emission_ * emissionStrength_; }
  float transmission() const { return transmission_; }
  ContainerId transmissionTexture() const { return transmissionTexture_; }
  float ior() const { return ior_; }
  ContainerId normalTexture() const { return normalTexture_; }  // tangent space
  float normalScale() const { return normalScale_; }

  void setBaseColor(const Vec3& v) { assign(BaseColor, baseColor_, v); }
  void setBaseColorTexture(ContainerId i) { assignReference(BaseColorTexture, baseColorTexture_, i); }
  void setOpacity(float v) { assign(Opacity, opacity_, v); }
  void setMetallic(float v) { assign(Metallic, metallic_, v); }
  void setRoughness(float v) { assign(Roughness, roughness_, v); }
  void setMetallicRoughnessTexture(ContainerId i) {
    assignReference(MetallicRoughnessTexture, metallicRoughnessTexture_, i);
  }
  void setSpecular(float v) { assign(Specular, specular_, v); }
  void setSpecularTexture(ContainerId i) { assignReference(SpecularTexture, specularTexture_, i); }
  void setEmission(const Vec3& v) { assign(Emission, emission_, v); }
  void setEmissionStrength(float v) { assign(EmissionStrength, emissionStrength_, v); }
  void setEmissionTexture(ContainerId i) { assignReference(EmissionTexture, emissionTexture_, i); }
  void setTransmission(float v) { assign(Transmission, transmission_, v); }
  void setTransmissionTexture(ContainerId i) { assignReference(TransmissionTexture, transmissionTexture_, i); }
  void setIor(float v) { assign(Ior, ior_, v); }
  void setNormalTexture(ContainerId i) { assignReference(NormalTexture, normalTexture_, i); }
  void setNormalScale(float v) { assign(NormalScale, normalScale_, v); }

  static constexpr auto fieldSpecs() {
    using M = SurfaceMaterial;
    return std::tuple{valueField("baseColor", &M::baseColor_),
                      referenceField("baseColorTexture", &M::baseColorTexture_, kImageTypes),
                      valueField("opacity", &M::opacity_),
                      valueField("metallic", &M::metallic_),
                      valueField("roughness", &M::roughness_),
                      referenceField("metallicRoughnessTexture", &M::metallicRoughnessTexture_, kImageTypes),
                      valueField("specular", &M::specular_),
                      referenceField("specularTexture", &M::specularTexture_, kImageTypes),
                      valueField("emission", &M::emission_),
                      valueField("emissionStrength", &M::emissionStrength_),
                      referenceField("emissionTexture", &M::emissionTexture_, kImageTypes),
                      valueField("transmission", &M::transmission_),
                      referenceField("transmissionTexture", &M::transmissionTexture_, kImageTypes),
                      valueField("ior", &M::ior_),
                      referenceField("normalTexture", &M::normalTexture_, kImageTypes),
                      valueField("normalScale", &M::normalScale_)};
  }

 private:
  Vec3 baseColor_{0.8f};
  ContainerId baseColorTexture_ = kNoContainer;
  float opacity_ = 1.0f;
  float metallic_ = 0.0f;
  float roughness_ = 0.5f;
  ContainerId metallicRoughnessTexture_ = kNoContainer;
  float specular_ = 1.0f;
  ContainerId specularTexture_ = kNoContainer;
  Vec3 emission_{0.0f};
  float emissionStrength_ = 1.0f;
  ContainerId emissionTexture_ = kNoContainer;
  float transmission_ = 0.0f;
  ContainerId transmissionTexture_ = kNoContainer;
  float ior_ = 1.5f;
  ContainerId normalTexture_ = kNoContainer;
  float normalScale_ = 1.0f;
};

}  // namespace tsr::sg
