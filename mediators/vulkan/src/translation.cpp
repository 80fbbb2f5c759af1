#include "translation.hpp"

#include "tsr/med/scene_values.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace tsr::med::vulkan_mediator {

namespace {
// The material models the rasterizer and the path tracer share.
vk::MaterialType typeOf(SurfaceClass c) {
  switch (c) {
    case SurfaceClass::Glass:
      return vk::MaterialType::Glass;
    case SurfaceClass::Dielectric:
      return vk::MaterialType::Dielectric;
    case SurfaceClass::Mirror:
      return vk::MaterialType::Mirror;
    case SurfaceClass::Conductor:
      return vk::MaterialType::Conductor;
    default:
      return vk::MaterialType::Diffuse;
  }
}
}  // namespace

vk::Material translateMaterial(const sg::Container* material, const TextureLookup& textures) {
  vk::Material m;
  if (!material) return m;  // default grey diffuse
  if (material->type() == sg::ContainerType::SimpleMaterial) {
    const auto& s = static_cast<const sg::SimpleMaterial&>(*material);
    m.baseColor = s.diffuse();
    m.baseColorTexture = s.diffuseTexture() ? textures(s.diffuseTexture()) : std::nullopt;
    m.emission = s.emission();
    m.opacity = std::clamp(1.0f - s.transparency(), 0.0f, 1.0f);
    return m;
  }
  if (material->type() != sg::ContainerType::SurfaceMaterial) return m;
  const auto& s = static_cast<const sg::SurfaceMaterial&>(*material);
  m.baseColor = s.baseColor();
  m.baseColorTexture = s.baseColorTexture() ? textures(s.baseColorTexture()) : std::nullopt;
  m.roughness = s.roughness();
  m.ior = s.ior();
  m.emission = s.emittedRadiance();
  m.emissionTexture = s.emissionTexture() ? textures(s.emissionTexture()) : std::nullopt;
  m.opacity = std::isfinite(s.opacity()) ? std::clamp(s.opacity(), 0.0f, 1.0f) : 1.0f;
  if (s.alphaMode() == sg::AlphaMode::Opaque) m.opacity = 1.0f;
  // A cut-off of 0 cuts nothing away: the surface is opaque.
  if (s.alphaMode() == sg::AlphaMode::Mask) {
    const float cutoff = std::isfinite(s.alphaCutoff()) ? std::clamp(s.alphaCutoff(), 0.0f, 1.0f) : 0.5f;
    m.alphaCutoff = cutoff;
    if (cutoff <= 0.0f) m.opacity = 1.0f;
  }
  m.type = typeOf(classify(s));
  m.normalTexture = s.normalTexture() ? textures(s.normalTexture()) : std::nullopt;
  m.occlusionTexture = s.occlusionTexture() ? textures(s.occlusionTexture()) : std::nullopt;
  m.occlusionStrength = std::isfinite(s.occlusionStrength()) ? std::clamp(s.occlusionStrength(), 0.0f, 1.0f) : 1.0f;
  const std::pair<sg::TextureSlot, vk::TextureSlot> slots[] = {
      {sg::TextureSlot::BaseColor, vk::TextureSlot::BaseColor},
      {sg::TextureSlot::Emission, vk::TextureSlot::Emission},
      {sg::TextureSlot::MetallicRoughness, vk::TextureSlot::MetallicRoughness},
      {sg::TextureSlot::Normal, vk::TextureSlot::Normal},
      {sg::TextureSlot::Occlusion, vk::TextureSlot::Occlusion}};
  for (const auto& [from, to] : slots) {
    const auto [row0, row1] = usableUvTransform(s, from);
    m.uv[static_cast<std::size_t>(to)] = {row0, row1};
  }
  m.normalScale = std::isfinite(s.normalScale()) ? s.normalScale() : 1.0f;
  // Every opaque surface takes glTF's BRDF (a dielectric's specular layer
  // over its diffuse base, or metal), as the path tracer renders it; smooth
  // mirrors and glass keep their reflection probe.
  const bool textured = s.metallicRoughnessTexture() != sg::kNoContainer;
  if (m.type == vk::MaterialType::Conductor || m.type == vk::MaterialType::Diffuse) {
    m.type = vk::MaterialType::MetallicRoughness;
    m.metallic = std::clamp(s.metallic(), 0.0f, 1.0f);
    m.metallicRoughnessTexture = textured ? textures(s.metallicRoughnessTexture()) : std::nullopt;
  }
  return m;
}

namespace {
// Coefficients the rasterizer cannot use (negative, NaN, infinite) count as none.
glm::vec3 usable(const glm::vec3& v) {
  glm::vec3 r;
  for (int c = 0; c < 3; ++c) r[c] = std::isfinite(v[c]) && v[c] > 0.0f ? v[c] : 0.0f;
  return r;
}
}  // namespace

vk::Medium translateMedium(const sg::VolumeMaterial& v) {
  const float g = std::isfinite(v.phaseG()) ? std::clamp(v.phaseG(), -0.99f, 0.99f) : 0.0f;
  return {usable(v.absorption()), usable(v.scattering()), usable(v.emission()), g};
}

vk::Material translateMaterial(const sg::Container* material, const sg::VolumeMaterial* volume,
                               const TextureLookup& textures) {
  vk::Material m = translateMaterial(material, textures);
  if (!volume) return m;
  const bool indexMatched = m.type == vk::MaterialType::Glass && std::abs(m.ior - 1.0f) < 1e-3f;
  if (!material || indexMatched) {
    m.type = vk::MaterialType::Glass;
    m.ior = 1.0f;
  }
  if (const vk::Medium medium = translateMedium(*volume); !medium.empty()) m.interior = medium;
  return m;
}

vk::Texture translateImage(const sg::Image& image) {
  const std::uint32_t w = image.width(), h = image.height(), n = image.channels();
  if (image.format() == sg::PixelFormat::UInt8) {
    // Keep 8 bits per channel on the GPU; expand to RGBA.
    std::vector<std::uint8_t> rgba(std::size_t{w} * h * 4, 255);
    const auto& px = image.pixels();
    for (std::size_t i = 0; i < std::size_t{w} * h; ++i) {
      const std::uint8_t* s = px.data() + i * n;
      std::uint8_t* d = rgba.data() + i * 4;
      if (n <= 2) {
        d[0] = d[1] = d[2] = s[0];
        if (n == 2) d[3] = s[1];
      } else {
        d[0] = s[0], d[1] = s[1], d[2] = s[2];
        if (n == 4) d[3] = s[3];
      }
    }
    return vk::Texture::fromRgba8(w, h, rgba, image.colorSpace() == sg::ColorSpace::SRGB);
  }
  auto texels = linearTexels(image);
  return vk::Texture::fromFloat(w, h, texels);
}

vk::Environment translateBackground(const sg::Scene& scene, sg::ContainerId id) {
  const auto* bg = scene.find<sg::Background>(id);
  if (!bg) return vk::Environment();
  vk::Environment sky = translateSky(scene, *bg);
  if (const auto* medium = scene.find<sg::VolumeMaterial>(bg->medium())) return sky.withFog(translateMedium(*medium));
  return sky;
}

vk::Environment translateSky(const sg::Scene& scene, const sg::Background& bg) {
  const float k = bg.intensity();
  switch (bg.kind()) {
    case sg::BackgroundKind::Gradient: {
      BakedSky sky = bakeGradient(bg);  // the same bake as the path tracer's, so the averages agree
      return vk::Environment::latLong(sky.width, sky.height, sky.texels, k);
    }
    case sg::BackgroundKind::Environment:
      if (const auto* image = scene.find<sg::Image>(bg.environment());
          image && !image->invalidReason() && image->width() > 0 && image->height() > 0) {
        auto texels = linearTexels(*image);
        return vk::Environment::latLong(image->width(), image->height(), texels, k);
      }
      return vk::Environment::constant(bg.color() * k);
    default:
      return vk::Environment::constant(bg.color() * k);
  }
}

glm::vec4 backgroundColour(const vk::Environment& environment) {
  return glm::vec4(environment.averageRadiance(), 0.0f);
}

vk::MeshData translateMesh(const sg::Geometry& geometry) {
  vk::MeshData data;
  data.positions = geometry.positions().toVector();
  data.normals = geometry.normals().toVector();
  data.uvs = geometry.uvs().toVector();
  data.indices = geometry.indices().toVector();
  data.primitive = primitiveOf(geometry);
  return data;
}

}  // namespace tsr::med::vulkan_mediator
