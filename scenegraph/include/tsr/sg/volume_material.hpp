#pragma once
// What fills a closed mesh, or the whole scene: the CommonVolumeShader of
// Schwenk's appendix 5.B. Emission, absorption and scattering, each a
// factor per unit length (scene units) times an optional texture, and a
// Henyey–Greenstein phase function with mean cosine g (0: isotropic). A
// geometry names it beside its surface material: the surface reflects and
// refracts at the boundary (a geometry without one is an index-matched
// boundary), the volume absorbs, scatters and emits inside; a background
// names it for fog everywhere outside. Textures are 3D: an image holds
// textureSlices slices of equal height stacked top (lowest z) to bottom,
// each a picture of the cross-section seen from +z (left: lowest x, top:
// highest y), so a plain 2D image is one slice, extended along z. They multiply their
// factor, are read as linear values (an sRGB image is decoded first),
// and are stretched over the geometry's object-space bounding box; the
// scene's medium ignores them. Rows past the last whole slice are unused.
//
// Units: absorption and scattering are coefficients sigma_a, sigma_s
// (1/unit); emission is radiance added per unit length, so a purely
// emitting slab of depth d adds emission * d.
#include "tsr/sg/container_of.hpp"

namespace tsr::sg {

class VolumeMaterial final : public ContainerOf<VolumeMaterial, ContainerType::VolumeMaterial> {
 public:
  enum Field : FieldIndex {
    Emission = kFirstOwnField,
    EmissionTexture,
    Absorption,
    AbsorptionTexture,
    Scattering,
    ScatteringTexture,
    PhaseG,
    TextureSlices
  };

  const Vec3& emission() const { return emission_; }
  ContainerId emissionTexture() const { return emissionTexture_; }
  const Vec3& absorption() const { return absorption_; }
  ContainerId absorptionTexture() const { return absorptionTexture_; }
  const Vec3& scattering() const { return scattering_; }
  ContainerId scatteringTexture() const { return scatteringTexture_; }
  float phaseG() const { return phaseG_; }                        // in (-1, 1); back-ends clamp to +-0.99
  std::uint32_t textureSlices() const { return textureSlices_; }  // 0 reads as 1

  void setEmission(const Vec3& v) { set<&VolumeMaterial::emission_>(v); }
  void setEmissionTexture(ContainerId image) { set<&VolumeMaterial::emissionTexture_>(image); }
  void setAbsorption(const Vec3& v) { set<&VolumeMaterial::absorption_>(v); }
  void setAbsorptionTexture(ContainerId image) { set<&VolumeMaterial::absorptionTexture_>(image); }
  void setScattering(const Vec3& v) { set<&VolumeMaterial::scattering_>(v); }
  void setScatteringTexture(ContainerId image) { set<&VolumeMaterial::scatteringTexture_>(image); }
  void setPhaseG(float g) { set<&VolumeMaterial::phaseG_>(g); }
  void setTextureSlices(std::uint32_t n) { set<&VolumeMaterial::textureSlices_>(n); }

  bool textured() const {
    return emissionTexture_ != kNoContainer || absorptionTexture_ != kNoContainer || scatteringTexture_ != kNoContainer;
  }

  static constexpr auto fieldSpecs() {
    using M = VolumeMaterial;
    return std::tuple{
        valueField(Emission, "emission", &M::emission_, &M::setEmission),
        referenceField(EmissionTexture, "emissionTexture", &M::emissionTexture_, kImageTypes, &M::setEmissionTexture),
        valueField(Absorption, "absorption", &M::absorption_, &M::setAbsorption),
        referenceField(AbsorptionTexture, "absorptionTexture", &M::absorptionTexture_, kImageTypes,
                       &M::setAbsorptionTexture),
        valueField(Scattering, "scattering", &M::scattering_, &M::setScattering),
        referenceField(ScatteringTexture, "scatteringTexture", &M::scatteringTexture_, kImageTypes,
                       &M::setScatteringTexture),
        valueField(PhaseG, "phaseG", &M::phaseG_, &M::setPhaseG),
        valueField(TextureSlices, "textureSlices", &M::textureSlices_, &M::setTextureSlices)};
  }

 private:
  Vec3 emission_{0.0f};
  ContainerId emissionTexture_ = kNoContainer;
  Vec3 absorption_{0.0f};
  ContainerId absorptionTexture_ = kNoContainer;
  Vec3 scattering_{0.0f};
  ContainerId scatteringTexture_ = kNoContainer;
  float phaseG_ = 0.0f;
  std::uint32_t textureSlices_ = 1;
};

}  // namespace tsr::sg
