#include "translation.hpp"

#include <cmath>
#include <cstring>

namespace tsr::med::embree_mediator {

embree::Material translateMaterial(const sg::Container* material, const TextureLookup& textures) {
  embree::Material m;
  if (!material) return m;  // default grey diffuse
  if (material->type() == sg::ContainerType::SimpleMaterial) {
    const auto& s = static_cast<const sg::SimpleMaterial&>(*material);
    m.baseColor = s.diffuse();
    m.baseColorTexture = s.diffuseTexture() ? textures(s.diffuseTexture()) : std::nullopt;
    m.emission = s.emission();
    return m;
  }
  const auto& s = static_cast<const sg::SurfaceMaterial&>(*material);
  m.baseColor = s.baseColor();
  m.baseColorTexture = s.baseColorTexture() ? textures(s.baseColorTexture()) : std::nullopt;
  m.roughness = s.roughness();
  m.ior = s.ior();
  m.emission = s.emittedRadiance();
  m.emissionTexture = s.emissionTexture() ? textures(s.emissionTexture()) : std::nullopt;
  if (s.transmission() > 0.5f)
    m.type = s.roughness() < 0.05f ? embree::MaterialType::Glass : embree::MaterialType::Dielectric;
  else if (s.metallic() > 0.5f)
    m.type = s.roughness() < 0.02f ? embree::MaterialType::Mirror : embree::MaterialType::Conductor;
  return m;
}

embree::Texture translateImage(const sg::Image& image) {
  const std::uint32_t w = image.width(), h = image.height(), n = image.channels();
  std::vector<glm::vec4> texels(std::size_t{w} * h, glm::vec4(0, 0, 0, 1));
  bool srgb = image.colorSpace() == sg::ColorSpace::SRGB;
  auto decode = [&](float v) { return srgb ? (v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f)) : v; };
  for (std::size_t i = 0; i < texels.size(); ++i) {
    for (std::uint32_t c = 0; c < n; ++c) {
      float v;
      if (image.format() == sg::PixelFormat::Float32) {
        std::memcpy(&v, image.pixels().data() + (i * n + c) * 4, 4);
      } else {
        v = static_cast<float>(image.pixels()[i * n + c]) / 255.0f;
        if (c < 3) v = decode(v);
      }
      texels[i][static_cast<int>(c)] = v;
    }
    if (n == 1) texels[i] = glm::vec4(texels[i].r, texels[i].r, texels[i].r, 1.0f);
    if (n == 2) texels[i] = glm::vec4(texels[i].r, texels[i].r, texels[i].r, texels[i].g);
  }
  return embree::Texture(w, h, std::move(texels));
}

embree::Light translateLight(const sg::Light& light, const glm::mat4& world) {
  glm::vec3 power = light.color() * light.intensity();
  glm::vec3 position = glm::vec3(world * glm::vec4(light.position(), 1.0f));
  glm::vec3 direction = glm::normalize(glm::vec3(world * glm::vec4(light.direction(), 0.0f)));
  switch (light.kind()) {
    case sg::LightKind::Spot:
      return embree::SpotLight{position, direction, power, light.innerConeAngle(), light.outerConeAngle()};
    case sg::LightKind::Directional: return embree::DirectionalLight{direction, power};
    default: return embree::PointLight{position, power};
  }
}

embree::Environment translateBackground(const sg::Scene& scene, sg::ContainerId id) {
  const auto* bg = scene.find<sg::Background>(id);
  if (!bg) return embree::Environment();
  float k = bg->intensity();
  switch (bg->kind()) {
    case sg::BackgroundKind::Gradient: {
      // Bake top-to-bottom into a lat-long map; rows follow elevation.
      constexpr std::uint32_t w = 8, h = 64;
      std::vector<glm::vec4> texels(w * h);
      for (std::uint32_t y = 0; y < h; ++y) {
        float t = (static_cast<float>(y) + 0.5f) / h;  // 0 at the zenith
        glm::vec3 c = glm::mix(bg->gradientTop(), bg->gradientBottom(), t);
        for (std::uint32_t x = 0; x < w; ++x) texels[y * w + x] = glm::vec4(c, 1.0f);
      }
      return embree::Environment::latLong(embree::Texture(w, h, std::move(texels)), k);
    }
    case sg::BackgroundKind::Environment:
      if (const auto* image = scene.find<sg::Image>(bg->environment()); image && !image->invalidReason())
        return embree::Environment::latLong(translateImage(*image), k);
      return embree::Environment::constant(bg->color() * k);
    default: return embree::Environment::constant(bg->color() * k);
  }
}

embree::MeshData translateMesh(const sg::Geometry& geometry) {
  embree::MeshData data;
  data.positions = geometry.positions();
  data.normals = geometry.normals();
  data.uvs = geometry.uvs();
  data.indices = geometry.indices();
  data.usage = geometry.motion() == sg::GeometryMotion::Animated ? embree::MeshUsage::Animated : embree::MeshUsage::Static;
  return data;
}

}  // namespace tsr::med::embree_mediator
