#include "translation.hpp"

#include <cmath>
#include <cstring>

namespace tsr::med::vulkan_mediator {

namespace {
float srgbToLinear(float v) { return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f); }

// Linear RGBA texels of any image (1 to 4 channels, 8-bit or float).
std::vector<glm::vec4> linearTexels(const sg::Image& image) {
  const std::uint32_t n = image.channels();
  std::vector<glm::vec4> texels(std::size_t{image.width()} * image.height(), glm::vec4(0, 0, 0, 1));
  const bool srgb = image.colorSpace() == sg::ColorSpace::SRGB;
  for (std::size_t i = 0; i < texels.size(); ++i) {
    for (std::uint32_t c = 0; c < n; ++c) {
      float v;
      if (image.format() == sg::PixelFormat::Float32) {
        std::memcpy(&v, image.pixels().data() + (i * n + c) * 4, 4);
      } else {
        v = static_cast<float>(image.pixels()[i * n + c]) / 255.0f;
        if (srgb && c < 3) v = srgbToLinear(v);
      }
      texels[i][static_cast<int>(c)] = v;
    }
    if (n == 1) texels[i] = glm::vec4(texels[i].r, texels[i].r, texels[i].r, 1.0f);
    if (n == 2) texels[i] = glm::vec4(texels[i].r, texels[i].r, texels[i].r, texels[i].g);
  }
  return texels;
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
  m.opacity = std::clamp(s.opacity(), 0.0f, 1.0f);
  if (s.transmission() > 0.5f)
    m.type = s.roughness() < 0.05f ? vk::MaterialType::Glass : vk::MaterialType::Dielectric;
  else if (s.metallic() > 0.5f)
    m.type = s.roughness() < 0.02f ? vk::MaterialType::Mirror : vk::MaterialType::Conductor;
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

vk::Light translateLight(const sg::Light& light, const glm::mat4& world) {
  glm::vec3 power = light.color() * light.intensity();
  glm::vec3 position = glm::vec3(world * glm::vec4(light.position(), 1.0f));
  glm::vec3 direction = glm::normalize(glm::vec3(world * glm::vec4(light.direction(), 0.0f)));
  switch (light.kind()) {
    case sg::LightKind::Spot:
      return vk::SpotLight{position, direction, power, light.innerConeAngle(), light.outerConeAngle()};
    case sg::LightKind::Directional: return vk::DirectionalLight{direction, power};
    default: return vk::PointLight{position, power};
  }
}

vk::Environment translateBackground(const sg::Scene& scene, sg::ContainerId id) {
  const auto* bg = scene.find<sg::Background>(id);
  if (!bg) return vk::Environment();
  const float k = bg->intensity();
  switch (bg->kind()) {
    case sg::BackgroundKind::Gradient: {
      // The same bake as the path tracer's, so the averages agree.
      constexpr std::uint32_t w = 8, h = 64;
      std::vector<glm::vec4> texels(w * h);
      for (std::uint32_t y = 0; y < h; ++y) {
        float t = (static_cast<float>(y) + 0.5f) / h;  // 0 at the zenith
        glm::vec3 c = glm::mix(bg->gradientTop(), bg->gradientBottom(), t);
        for (std::uint32_t x = 0; x < w; ++x) texels[y * w + x] = glm::vec4(c, 1.0f);
      }
      return vk::Environment::latLong(w, h, texels, k);
    }
    case sg::BackgroundKind::Environment:
      if (const auto* image = scene.find<sg::Image>(bg->environment());
          image && !image->invalidReason() && image->width() > 0 && image->height() > 0) {
        auto texels = linearTexels(*image);
        return vk::Environment::latLong(image->width(), image->height(), texels, k);
      }
      return vk::Environment::constant(bg->color() * k);
    default: return vk::Environment::constant(bg->color() * k);
  }
}

glm::vec4 backgroundColour(const vk::Environment& environment) { return glm::vec4(environment.averageRadiance(), 0.0f); }

vk::MeshData translateMesh(const sg::Geometry& geometry) {
  vk::MeshData data;
  data.positions = geometry.positions();
  data.normals = geometry.normals();
  data.uvs = geometry.uvs();
  data.indices = geometry.indices();
  return data;
}

}  // namespace tsr::med::vulkan_mediator
