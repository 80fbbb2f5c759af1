#include "translation.hpp"

#include "tsr/med/scene_values.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace tsr::med::embree_mediator {

namespace {
// Coefficients as the back-end accepts them: finite and not negative.
glm::vec3 coefficient(const glm::vec3& v) {
  glm::vec3 out;
  for (int c = 0; c < 3; ++c) out[c] = std::isfinite(v[c]) ? std::max(v[c], 0.0f) : 0.0f;
  return out;
}
}  // namespace

embree::Medium translateMedium(const sg::VolumeMaterial& v) {
  embree::Medium m;
  m.absorption = coefficient(v.absorption());
  m.scattering = coefficient(v.scattering());
  m.emission = coefficient(v.emission());
  m.g = std::isfinite(v.phaseG()) ? std::clamp(v.phaseG(), -0.99f, 0.99f) : 0.0f;
  return m;
}

embree::Medium translateMedium(const sg::VolumeMaterial& v, const TextureLookup& textures) {
  embree::Medium m = translateMedium(v);
  auto texture = [&](sg::ContainerId id) { return id != sg::kNoContainer ? textures(id) : std::nullopt; };
  m.absorptionTexture = texture(v.absorptionTexture());
  m.scatteringTexture = texture(v.scatteringTexture());
  m.emissionTexture = texture(v.emissionTexture());
  m.textureSlices = std::max<std::uint32_t>(v.textureSlices(), 1);
  return m;
}

embree::Material translateMaterial(const sg::Container* material, const sg::VolumeMaterial* volume,
                                   const TextureLookup& textures) {
  embree::Material m = translateSurface(material, textures);
  if (volume) {
    // A medium alone, or behind smooth glass of index 1 (how a glTF file
    // says "no surface"): an index-matched boundary rays and shadow rays cross.
    const bool indexMatched = embree::closestClass(m) == embree::MaterialType::Glass && std::abs(m.ior - 1.0f) < 1e-3f;
    if (!material || indexMatched) m.type = embree::MaterialType::Interface;
    if (const embree::Medium medium = translateMedium(*volume, textures); !medium.empty()) m.interior = medium;
  }
  return m;
}

namespace {
embree::UvTransform uvTransform(const sg::SurfaceMaterial& s, sg::TextureSlot slot) {
  const auto [row0, row1] = usableUvTransform(s, slot);
  return {row0, row1};
}
}  // namespace

embree::Material translateSurface(const sg::Container* material, const TextureLookup& textures) {
  embree::Material m;
  if (!material) return m;  // default grey diffuse
  if (material->type() == sg::ContainerType::SimpleMaterial) {
    const auto& s = static_cast<const sg::SimpleMaterial&>(*material);
    m.baseColor = s.diffuse();
    m.baseColorTexture = s.diffuseTexture() ? textures(s.diffuseTexture()) : std::nullopt;
    m.emission = s.emission();
    return m;
  }
  // glTF's metallic-roughness BSDF from the continuous parameters: no
  // thresholds, textures vary them per hit.
  const auto& s = static_cast<const sg::SurfaceMaterial&>(*material);
  auto texture = [&](sg::ContainerId id) { return id != sg::kNoContainer ? textures(id) : std::nullopt; };
  auto unit = [](float v, float fallback) { return std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : fallback; };
  m.type = embree::MaterialType::MetallicRoughness;
  m.baseColor = s.baseColor();
  m.baseColorTexture = texture(s.baseColorTexture());
  m.roughness = s.roughness();
  m.metallic = unit(s.metallic(), 0.0f);
  m.specular = unit(s.specular(), 1.0f);
  m.transmission = unit(s.transmission(), 0.0f);
  m.metallicRoughnessTexture = texture(s.metallicRoughnessTexture());
  m.transmissionTexture = texture(s.transmissionTexture());
  m.normalTexture = texture(s.normalTexture());
  m.normalScale = std::isfinite(s.normalScale()) ? s.normalScale() : 1.0f;
  m.ior = s.ior();
  m.emission = s.emittedRadiance();
  m.emissionTexture = texture(s.emissionTexture());
  m.baseColorUv = uvTransform(s, sg::TextureSlot::BaseColor);
  m.emissionUv = uvTransform(s, sg::TextureSlot::Emission);
  m.metallicRoughnessUv = uvTransform(s, sg::TextureSlot::MetallicRoughness);
  m.transmissionUv = uvTransform(s, sg::TextureSlot::Transmission);
  m.normalUv = uvTransform(s, sg::TextureSlot::Normal);
  m.opacity = std::isfinite(s.opacity()) ? std::clamp(s.opacity(), 0.0f, 1.0f) : 1.0f;
  m.alphaCutoff = std::isfinite(s.alphaCutoff()) ? s.alphaCutoff() : 0.5f;
  switch (s.alphaMode()) {
    case sg::AlphaMode::Mask:
      m.alphaMode = embree::AlphaMode::Mask;
      break;
    case sg::AlphaMode::Blend:
      m.alphaMode = embree::AlphaMode::Blend;
      break;
    default:
      m.alphaMode = embree::AlphaMode::Opaque;
  }
  return m;
}

embree::Texture translateImage(const sg::Image& image) {
  return embree::Texture(image.width(), image.height(), linearTexels(image));
}

embree::Environment translateBackground(const sg::Scene& scene, sg::ContainerId id) {
  const auto* bg = scene.find<sg::Background>(id);
  if (!bg) return embree::Environment();
  std::optional<embree::Medium> fog;
  if (const auto* medium = scene.find<sg::VolumeMaterial>(bg->medium())) fog = translateMedium(*medium);
  return translateSky(scene, *bg).withMedium(fog);
}

embree::Environment translateSky(const sg::Scene& scene, const sg::Background& background) {
  const auto* bg = &background;
  float k = bg->intensity();
  switch (bg->kind()) {
    case sg::BackgroundKind::Gradient: {
      BakedSky sky = bakeGradient(*bg);
      return embree::Environment::latLong(embree::Texture(sky.width, sky.height, std::move(sky.texels)), k);
    }
    case sg::BackgroundKind::Environment:
      if (const auto* image = scene.find<sg::Image>(bg->environment()); image && !image->invalidReason())
        return embree::Environment::latLong(translateImage(*image), k);
      return embree::Environment::constant(bg->color() * k);
    default:
      return embree::Environment::constant(bg->color() * k);
  }
}

namespace {
template <class T>
backend::SharedElements<T> held(std::shared_ptr<const sg::ArrayElements<T>> elements) {
  const std::span<const T> view = sg::elementsOf(elements);  // before the pointer moves
  return backend::SharedElements<T>(view, std::move(elements));
}
}  // namespace

embree::MeshData translateMesh(const sg::Geometry& geometry) {
  // The replica's arrays themselves: the path tracer holds no copy of them.
  embree::MeshData data;
  data.positions = held(geometry.sharedPositions());
  data.normals = held(geometry.sharedNormals());
  data.uvs = held(geometry.sharedUvs());
  data.indices = held(geometry.sharedIndices());
  data.usage =
      geometry.motion() == sg::GeometryMotion::Animated ? embree::MeshUsage::Animated : embree::MeshUsage::Static;
  return data;
}

}  // namespace tsr::med::embree_mediator
