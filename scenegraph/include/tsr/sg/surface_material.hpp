#pragma once
// A portable physically based material in the spirit of X3D's
// CommonSurfaceShader (dissertation appendix 5.A) and glTF's metallic-
// roughness model. Every factor has an optional texture that multiplies it.
#include <utility>
#include <vector>

#include "tsr/sg/container_of.hpp"

namespace tsr::sg {

// How alpha (opacity x the base colour texture's alpha) covers a surface,
// as glTF's alphaMode: Opaque ignores it, Mask cuts out where it is below
// alphaCutoff, Blend covers that share of the surface. Blend is the
// default, so a material of opacity 1 is opaque.
enum class AlphaMode : std::uint8_t { Opaque, Mask, Blend, Count };

// The texture slots of a SurfaceMaterial, in the order of its uvTransforms.
enum class TextureSlot : std::uint8_t {
  BaseColor,
  MetallicRoughness,
  Specular,
  Emission,
  Transmission,
  Normal,
  Occlusion,
  Count
};

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
    Alpha,
    AlphaCutoff,
    OcclusionTexture,
    OcclusionStrength,
    UvTransforms,
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
  AlphaMode alphaMode() const { return alphaMode_; }
  float alphaCutoff() const { return alphaCutoff_; }
  // Ambient occlusion in the red channel (glTF), for back-ends that do not
  // find it themselves; strength 0 turns it off.
  ContainerId occlusionTexture() const { return occlusionTexture_; }
  float occlusionStrength() const { return occlusionStrength_; }
  // Empty, or two rows of an affine map of texture coordinates per slot
  // (TextureSlot order): uv' = (dot(row0, (u, v, 1)), dot(row1, (u, v, 1))),
  // as KHR_texture_transform's offset x rotation x scale.
  const std::vector<Vec3>& uvTransforms() const { return uvTransforms_; }
  static constexpr std::size_t kUvTransformRows = 2 * static_cast<std::size_t>(TextureSlot::Count);
  // The map of one slot: (row0, row1), identity when there is none.
  std::pair<Vec3, Vec3> uvTransform(TextureSlot slot) const {
    const auto i = 2 * static_cast<std::size_t>(slot);
    if (uvTransforms_.size() != kUvTransformRows) return {Vec3(1, 0, 0), Vec3(0, 1, 0)};
    return {uvTransforms_[i], uvTransforms_[i + 1]};
  }

  void setBaseColor(const Vec3& v) { set<&SurfaceMaterial::baseColor_>(v); }
  void setBaseColorTexture(ContainerId i) { set<&SurfaceMaterial::baseColorTexture_>(i); }
  void setOpacity(float v) { set<&SurfaceMaterial::opacity_>(v); }
  void setMetallic(float v) { set<&SurfaceMaterial::metallic_>(v); }
  void setRoughness(float v) { set<&SurfaceMaterial::roughness_>(v); }
  void setMetallicRoughnessTexture(ContainerId i) { set<&SurfaceMaterial::metallicRoughnessTexture_>(i); }
  void setSpecular(float v) { set<&SurfaceMaterial::specular_>(v); }
  void setSpecularTexture(ContainerId i) { set<&SurfaceMaterial::specularTexture_>(i); }
  void setEmission(const Vec3& v) { set<&SurfaceMaterial::emission_>(v); }
  void setEmissionStrength(float v) { set<&SurfaceMaterial::emissionStrength_>(v); }
  void setEmissionTexture(ContainerId i) { set<&SurfaceMaterial::emissionTexture_>(i); }
  void setTransmission(float v) { set<&SurfaceMaterial::transmission_>(v); }
  void setTransmissionTexture(ContainerId i) { set<&SurfaceMaterial::transmissionTexture_>(i); }
  void setIor(float v) { set<&SurfaceMaterial::ior_>(v); }
  void setNormalTexture(ContainerId i) { set<&SurfaceMaterial::normalTexture_>(i); }
  void setNormalScale(float v) { set<&SurfaceMaterial::normalScale_>(v); }
  void setAlphaMode(AlphaMode m) { set<&SurfaceMaterial::alphaMode_>(m); }
  void setAlphaCutoff(float v) { set<&SurfaceMaterial::alphaCutoff_>(v); }
  void setOcclusionTexture(ContainerId i) { set<&SurfaceMaterial::occlusionTexture_>(i); }
  void setOcclusionStrength(float v) { set<&SurfaceMaterial::occlusionStrength_>(v); }
  void setUvTransforms(std::vector<Vec3> rows) { set<&SurfaceMaterial::uvTransforms_>(std::move(rows)); }

  static constexpr auto fieldSpecs() {
    using M = SurfaceMaterial;
    return std::tuple{
        valueField(BaseColor, "baseColor", &M::baseColor_, &M::setBaseColor),
        referenceField(BaseColorTexture, "baseColorTexture", &M::baseColorTexture_, kImageTypes,
                       &M::setBaseColorTexture),
        valueField(Opacity, "opacity", &M::opacity_, &M::setOpacity),
        valueField(Metallic, "metallic", &M::metallic_, &M::setMetallic),
        valueField(Roughness, "roughness", &M::roughness_, &M::setRoughness),
        referenceField(MetallicRoughnessTexture, "metallicRoughnessTexture", &M::metallicRoughnessTexture_, kImageTypes,
                       &M::setMetallicRoughnessTexture),
        valueField(Specular, "specular", &M::specular_, &M::setSpecular),
        referenceField(SpecularTexture, "specularTexture", &M::specularTexture_, kImageTypes, &M::setSpecularTexture),
        valueField(Emission, "emission", &M::emission_, &M::setEmission),
        valueField(EmissionStrength, "emissionStrength", &M::emissionStrength_, &M::setEmissionStrength),
        referenceField(EmissionTexture, "emissionTexture", &M::emissionTexture_, kImageTypes, &M::setEmissionTexture),
        valueField(Transmission, "transmission", &M::transmission_, &M::setTransmission),
        referenceField(TransmissionTexture, "transmissionTexture", &M::transmissionTexture_, kImageTypes,
                       &M::setTransmissionTexture),
        valueField(Ior, "ior", &M::ior_, &M::setIor),
        referenceField(NormalTexture, "normalTexture", &M::normalTexture_, kImageTypes, &M::setNormalTexture),
        valueField(NormalScale, "normalScale", &M::normalScale_, &M::setNormalScale),
        valueField(Alpha, "alphaMode", &M::alphaMode_, &M::setAlphaMode),
        valueField(AlphaCutoff, "alphaCutoff", &M::alphaCutoff_, &M::setAlphaCutoff),
        referenceField(OcclusionTexture, "occlusionTexture", &M::occlusionTexture_, kImageTypes,
                       &M::setOcclusionTexture),
        valueField(OcclusionStrength, "occlusionStrength", &M::occlusionStrength_, &M::setOcclusionStrength),
        arrayField(UvTransforms, "uvTransforms", &M::uvTransforms_, &M::setUvTransforms)};
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
  AlphaMode alphaMode_ = AlphaMode::Blend;
  float alphaCutoff_ = 0.5f;
  ContainerId occlusionTexture_ = kNoContainer;
  float occlusionStrength_ = 1.0f;
  std::vector<Vec3> uvTransforms_;
};

}  // namespace tsr::sg
