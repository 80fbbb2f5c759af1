#include "test_scenes.hpp"

#include <gtest/gtest.h>

namespace tsr::embree::test {
namespace {

constexpr float kAlbedo = 0.5f;

// Lat-long map whose upper half has radiance `sky` plus a bright sun patch,
// and whose lower half is `ground`. height is even, so the horizon is a row
// boundary.
Texture skyMap(float sky, float ground, float sun) {
  const std::uint32_t w = 32, h = 16;
  std::vector<glm::vec4> t(w * h);
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x) {
      float v = y < h / 2 ? sky : ground;
      if (y == 3 && (x == 10 || x == 11)) v = sun;
      t[y * w + x] = glm::vec4(v, v, v, 1.0f);
    }
  return Texture(w, h, std::move(t));
}

FrameBuffer renderPlane(const Environment& env, LightSampling mode) {
  Scene scene(sharedDevice());
  Material m;
  m.baseColor = glm::vec3(kAlbedo);
  scene.addInstance(scene.addMesh(quad({-1000, 0, 1000}, {1000, 0, 1000}, {1000, 0, -1000}, {-1000, 0, -1000})),
                    scene.addMaterial(m), glm::mat4(1.0f));
  scene.setEnvironment(env);
  RenderSettings s;
  s.maxDepth = 1;
  s.samplesPerPass = 16;
  s.lightSampling = mode;
  Renderer renderer(s);
  FrameBuffer fb(16, 16);
  Camera camera = Camera::lookAt({0, 1, 0}, {0, 0, 0}, {0, 0, -1}, glm::radians(60.0f), 1.0f);
  render(renderer, scene, camera, Region::full(16, 16), fb, 4);
  return fb;
}

// A diffuse plane sees only the upper hemisphere: L = albedo * sky.
TEST(EmbreeEnvironment, UpperHemisphereIrradianceIsAnalytic) {
  Environment env = Environment::latLong(skyMap(0.8f, 5.0f, 0.8f));
  for (LightSampling mode : {LightSampling::Mis, LightSampling::LightOnly, LightSampling::BsdfOnly}) {
    FrameBuffer fb = renderPlane(env, mode);
    float want = kAlbedo * 0.8f;
    EXPECT_NEAR(meanColour(fb).x, want, 4.0f * meanStandardError(fb) + 0.003f) << "mode " << int(mode);
  }
}

// With a small bright sun, importance sampling must agree with BSDF sampling,
// and MIS must be much less noisy than BSDF sampling alone.
TEST(EmbreeEnvironment, ImportanceSamplingAgreesAndReducesNoise) {
  Environment env = Environment::latLong(skyMap(0.1f, 0.0f, 400.0f));
  FrameBuffer mis = renderPlane(env, LightSampling::Mis);
  FrameBuffer bsdf = renderPlane(env, LightSampling::BsdfOnly);
  float m = meanColour(mis).x, b = meanColour(bsdf).x;
  float sm = meanStandardError(mis), sb = meanStandardError(bsdf);
  EXPECT_NEAR(m, b, 4.0f * std::hypot(sm, sb)) << m << " vs " << b;
  EXPECT_LT(sm * 3.0f, sb);
}

TEST(EmbreeEnvironment, ConstantMapEqualsConstantColour) {
  Environment map =
      Environment::latLong(Texture(64, 32, std::vector<glm::vec4>(64 * 32, glm::vec4(0.3f, 0.4f, 0.5f, 1.0f))));
  Environment colour = Environment::constant({0.3f, 0.4f, 0.5f});
  glm::vec3 d = glm::normalize(glm::vec3(0.3f, 0.5f, -0.2f));
  EXPECT_EQ(map.radiance(d), colour.radiance(d));
  // Rows are weighted by sin(theta) at their centre, so the pdf is uniform up to the row height.
  EXPECT_NEAR(map.pdf(d), 1.0f / (4.0f * kPi), 0.02f / (4.0f * kPi));
  FrameBuffer fb = renderPlane(map, LightSampling::Mis);
  EXPECT_NEAR(meanColour(fb).z, kAlbedo * 0.5f, 4.0f * meanStandardError(fb) + 0.003f);
}

TEST(EmbreeEnvironment, SampledDirectionsHaveConsistentPdf) {
  Environment env = Environment::latLong(skyMap(0.1f, 0.05f, 50.0f));
  for (int i = 0; i < 200; ++i) {
    glm::vec2 u{(float(i % 20) + 0.37f) / 20.0f, (float(i / 20) + 0.61f) / 10.0f};
    Environment::Sample s = env.sample(u);
    ASSERT_GT(s.pdf, 0.0f);
    EXPECT_NEAR(env.pdf(s.direction), s.pdf, 1e-3f * s.pdf);
    EXPECT_EQ(env.radiance(s.direction), s.radiance);
  }
}

}  // namespace
}  // namespace tsr::embree::test
