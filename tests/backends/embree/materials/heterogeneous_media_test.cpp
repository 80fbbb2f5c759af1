// Textured (heterogeneous) media, traced by delta tracking and, for shadow
// rays, ratio tracking; checked against what is known exactly: a slab
// whose density falls along the view passes exp(-optical depth) in each
// colour; its emission adds up to the integral; a constant texture renders
// like the homogeneous medium of the same coefficients (through camera
// paths and shadow rays alike); white scattering conserves energy; the
// textures move with their instance; and renders are bitwise alike on one
// thread and two.
#include <gtest/gtest.h>

#include <cmath>

#include "test_scenes.hpp"

namespace tsr::embree::test {
namespace {

// A grey texture of `slices` slices of one texel each, values along z.
Texture zRamp(std::vector<float> values) {
  std::vector<glm::vec4> texels;
  for (float v : values) texels.emplace_back(v, v, v, 1.0f);
  return Texture(1, std::uint32_t(values.size()), std::move(texels));
}

struct Slab {
  Scene scene{sharedDevice()};
  Camera camera = Camera::lookAt({0, 0, 6}, {0, 0, 0}, {0, 1, 0}, glm::radians(1.0f), 1.0f);
  InstanceId instance{};
};

// A 2-unit slab (z from -1 to 1) of `medium` with no surface, whose
// absorption, scattering or emission (`which`) is multiplied by `texture`.
void fill(Slab& v, Medium medium, const Texture& texture, std::optional<TextureId> Medium::*which,
          const glm::vec3& sky) {
  medium.*which = v.scene.addTexture(texture);
  Material boundary;
  boundary.type = MaterialType::Interface;
  boundary.interior = medium;
  v.instance = v.scene.addInstance(v.scene.addMesh(box({-5, -5, -1}, {5, 5, 1})), v.scene.addMaterial(boundary),
                                   glm::mat4(1.0f));
  v.scene.setEnvironment(Environment::constant(sky));
}

glm::vec3 renderMean(Scene& scene, const Camera& camera, int passes, int threads = 0, FrameBuffer* out = nullptr,
                     std::uint32_t size = 16) {
  RenderSettings s;
  s.samplesPerPass = 16;
  s.threads = threads;
  Renderer renderer(s);
  FrameBuffer fb(size, size);
  render(renderer, scene, camera, Region::full(size, size), fb, passes);
  if (out) *out = fb;
  return meanColour(fb);
}

// Two slices, 1 then 0: between their centres (z = 0.25 and 0.75 of the
// box) the density falls linearly, and it is constant beyond, so the mean
// density along z is 0.25 + 0.5 * 0.5 = 0.5, over a depth of 2.
constexpr float kRampIntegral = 0.5f * 2.0f;

TEST(EmbreeHeterogeneousMedia, ASlabPassesExpOfMinusItsOpticalDepthInEachColour) {
  Slab v;
  Medium m;
  m.absorption = {0.5f, 1.0f, 2.0f};
  m.textureSlices = 2;
  fill(v, m, zRamp({1.0f, 0.0f}), &Medium::absorptionTexture, glm::vec3(1.0f));
  const glm::vec3 c = renderMean(v.scene, v.camera, 32);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], std::exp(-m.absorption[k] * kRampIntegral), 0.01f) << k;
}

TEST(EmbreeHeterogeneousMedia, EmissionAddsUpToItsIntegral) {
  for (float absorption : {0.0f, 0.5f}) {
    Slab v;
    Medium m;
    m.emission = {0.25f, 0.5f, 0.1f};
    m.absorption = glm::vec3(absorption);
    m.textureSlices = 2;
    fill(v, m, zRamp({1.0f, 0.0f}), &Medium::emissionTexture, glm::vec3(0.0f));
    const glm::vec3 c = renderMean(v.scene, v.camera, 16);
    // Emission density e(z) seen through the homogeneous absorber behind
    // the camera's side: integrate e(z) exp(-a (distance from the front)).
    double expected = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      const double w = (i + 0.5) / n;  // 0 at z = -1 (far side), 1 at z = 1 (the camera's side)
      const double density = std::clamp(1.0 - (w - 0.25) / 0.5, 0.0, 1.0);
      expected += density * std::exp(-absorption * 2.0 * (1.0 - w)) * 2.0 / n;
    }
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(c[k], m.emission[k] * expected, 0.02f * m.emission[k] * expected) << "absorption " << absorption;
  }
}

// A scattering box on a floor under a lamp, in which light arrives by
// camera paths (delta tracking) and by shadow rays (ratio tracking).
glm::vec3 litBox(const Medium& medium, const Texture* texture, int passes) {
  Scene scene(sharedDevice());
  floorUnderLamp(scene);
  Medium m = medium;
  if (texture) {
    m.scatteringTexture = scene.addTexture(*texture);
    m.absorptionTexture = m.scatteringTexture;
  }
  Material boundary;
  boundary.type = MaterialType::Interface;
  boundary.interior = m;
  scene.addInstance(scene.addMesh(box({-1, 0, -1}, {1, 2, 1})), scene.addMaterial(boundary), glm::mat4(1.0f));
  Camera camera = Camera::lookAt({0, 2, 7}, {0, 1, 0}, {0, 1, 0}, glm::radians(40.0f), 1.0f);
  return renderMean(scene, camera, passes, 0, nullptr, 24);
}

TEST(EmbreeHeterogeneousMedia, AConstantTextureRendersLikeTheHomogeneousMedium) {
  Medium homogeneous;
  homogeneous.scattering = {0.8f, 0.6f, 0.4f};
  homogeneous.absorption = glm::vec3(0.2f);
  homogeneous.g = -0.3f;
  Medium textured = homogeneous;
  textured.scattering *= 4.0f;
  textured.absorption *= 4.0f;
  const Texture quarter(2, 2, std::vector<glm::vec4>(4, glm::vec4(0.25f)));
  const glm::vec3 a = litBox(homogeneous, nullptr, 16);
  const glm::vec3 b = litBox(textured, &quarter, 16);
  for (int k = 0; k < 3; ++k) {
    EXPECT_GT(a[k], 0.01f) << k;
    EXPECT_NEAR(b[k], a[k], 0.02f * a[k]) << k;
  }
}

TEST(EmbreeHeterogeneousMedia, AWhiteScatteringCloudInAWhiteFurnaceNeitherGainsNorLoses) {
  Scene scene(sharedDevice());
  // A lumpy density: 4 x 4 texels in 4 slices, from 0 to 3.
  std::vector<glm::vec4> texels;
  for (int i = 0; i < 64; ++i) texels.emplace_back(float((i * 7) % 13) / 4.0f);
  Medium white;
  white.scattering = glm::vec3(1.5f);
  white.g = 0.4f;
  white.textureSlices = 4;
  white.scatteringTexture = scene.addTexture(Texture(4, 16, texels));
  const glm::vec3 c = furnaceMean(scene, white);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], 0.5f, 0.005f) << k;  // 1 %
}

// Mean of the left and right halves of a frame.
std::pair<float, float> halves(const FrameBuffer& fb) {
  double left = 0, right = 0;
  for (std::uint32_t y = 0; y < fb.height(); ++y)
    for (std::uint32_t x = 0; x < fb.width(); ++x) (x < fb.width() / 2 ? left : right) += fb.colour(x, y).g;
  return {float(left), float(right)};
}

TEST(EmbreeHeterogeneousMedia, TheTexturesMoveWithTheirInstance) {
  // Absorbing on the left (lowest x) half of the box only.
  Slab v;
  v.camera = Camera::lookAt({0, 0, 6}, {0, 0, 0}, {0, 1, 0}, glm::radians(60.0f), 1.0f);
  Medium m;
  m.absorption = glm::vec3(2.0f);
  fill(v, m, Texture(2, 1, {glm::vec4(1.0f), glm::vec4(0.0f)}), &Medium::absorptionTexture, glm::vec3(1.0f));
  FrameBuffer fb(16, 16);
  renderMean(v.scene, v.camera, 2, 0, &fb);
  auto [left, right] = halves(fb);
  EXPECT_LT(left, 0.5f * right);
  // Turned half a turn about y, the absorbing half is on the right.
  v.scene.setInstanceTransform(v.instance, glm::mat4(-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1));
  renderMean(v.scene, v.camera, 2, 0, &fb);
  std::tie(left, right) = halves(fb);
  EXPECT_LT(right, 0.5f * left);
}

TEST(EmbreeHeterogeneousMedia, RendersAreBitwiseAlikeOnOneThreadAndTwo) {
  FrameBuffer one(16, 16), two(16, 16);
  for (FrameBuffer* out : {&one, &two}) {
    Slab v;
    Medium m;
    m.absorption = glm::vec3(0.1f);
    m.scattering = {0.4f, 0.5f, 0.6f};
    m.emission = glm::vec3(0.05f);
    m.g = 0.3f;
    m.textureSlices = 2;
    fill(v, m, zRamp({1.0f, 0.2f}), &Medium::scatteringTexture, glm::vec3(0.8f));
    renderMean(v.scene, v.camera, 2, out == &one ? 1 : 2, out);
  }
  EXPECT_TRUE(identical(one, two));
}

}  // namespace
}  // namespace tsr::embree::test
