#include "test_scenes.hpp"

#include <gtest/gtest.h>

namespace tsr::embree::test {
namespace {

constexpr std::uint32_t kSize = 24;
constexpr float kAlbedo = 0.6f;
const glm::vec3 kEye{0.3f, 4.0f, 0.2f};
const Camera kCamera = Camera::lookAt(kEye, {0.3f, 0.0f, 0.2f}, {0, 0, -1}, glm::radians(70.0f), 1.0f);

// A large diffuse floor (y = 0) seen from above, lit only by `light`.
FrameBuffer renderFloor(const Light& light) {
  Scene scene(sharedDevice());
  Material m;
  m.baseColor = glm::vec3(kAlbedo);
  scene.addInstance(scene.addMesh(quad({-50, 0, 50}, {50, 0, 50}, {50, 0, -50}, {-50, 0, -50})), scene.addMaterial(m),
                    glm::mat4(1.0f));
  scene.addLight(light);
  RenderSettings s;
  s.maxDepth = 1;
  s.samplesPerPass = 16;
  Renderer renderer(s);
  FrameBuffer fb(kSize, kSize);
  render(renderer, scene, kCamera, Region::full(kSize, kSize), fb, 4);
  return fb;
}

// Averages f(point on the floor) over an 8x8 grid inside pixel (px, py).
template <class F>
float pixelAverage(std::uint32_t px, std::uint32_t py, F f) {
  glm::mat3 rot(kCamera.cameraToWorld);
  double sum = 0.0;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) {
      float cx = kCamera.left + (kCamera.right - kCamera.left) * ((float(px) + (float(i) + 0.5f) / 8) / kSize);
      float cy = kCamera.top - (kCamera.top - kCamera.bottom) * ((float(py) + (float(j) + 0.5f) / 8) / kSize);
      glm::vec3 d = rot * glm::vec3(cx, cy, -kCamera.near);  // the window lies on the near plane
      glm::vec3 p = kEye + d * (-kEye.y / d.y);
      sum += f(p);
    }
  return float(sum / 64.0);
}

TEST(EmbreeDirectLight, PointLightMatchesAnalyticIrradiance) {
  const glm::vec3 lp{0.5f, 1.5f, -0.3f};
  const float intensity = 8.0f;
  FrameBuffer fb = renderFloor(PointLight{lp, glm::vec3(intensity)});
  auto expected = [&](const glm::vec3& p) {
    glm::vec3 d = lp - p;
    float d2 = glm::dot(d, d);
    return kAlbedo / kPi * intensity * (d.y / std::sqrt(d2)) / d2;
  };
  for (std::uint32_t y = 0; y < kSize; y += 3)
    for (std::uint32_t x = 0; x < kSize; x += 3) {
      float want = pixelAverage(x, y, expected);
      // Jitter inside the pixel is the only noise: allow 4 standard errors.
      float se = std::sqrt(fb.variance(Channel::Colour, x, y).x / float(fb.sampleCount(x, y)));
      EXPECT_NEAR(fb.colour(x, y).x, want, 4.0f * se + 0.002f * want) << "pixel " << x << "," << y;
    }
}

TEST(EmbreeDirectLight, DirectionalLightGivesUniformRadiance) {
  glm::vec3 dir = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  FrameBuffer fb = renderFloor(DirectionalLight{dir, glm::vec3(2.0f)});
  float want = kAlbedo / kPi * 2.0f * -dir.y;
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) EXPECT_NEAR(fb.colour(x, y).y, want, 1e-4f * want);
  EXPECT_EQ(fb.variance(Channel::Colour, 5, 5), glm::vec3(0.0f));
  EXPECT_EQ(fb.mean(Channel::Indirect, 5, 5), glm::vec3(0.0f));
}

TEST(EmbreeDirectLight, SpotLightIsPointLightInsideConeAndDarkOutside) {
  const glm::vec3 lp{0.3f, 2.0f, 0.2f};
  FrameBuffer fb = renderFloor(SpotLight{lp, {0, -1, 0}, glm::vec3(6.0f), 0.35f, 0.45f});
  int inside = 0, outside = 0;
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      // Classify by the angle to the pixel's whole footprint.
      float minAngle = 10.0f, maxAngle = 0.0f;
      pixelAverage(x, y, [&](const glm::vec3& p) {
        float a = std::acos(glm::dot(glm::normalize(p - lp), glm::vec3(0, -1, 0)));
        minAngle = std::min(minAngle, a);
        maxAngle = std::max(maxAngle, a);
        return 0.0f;
      });
      if (maxAngle < 0.34f) {
        float want = pixelAverage(x, y, [&](const glm::vec3& p) {
          glm::vec3 d = lp - p;
          float d2 = glm::dot(d, d);
          return kAlbedo / kPi * 6.0f * (d.y / std::sqrt(d2)) / d2;
        });
        float se = std::sqrt(fb.variance(Channel::Colour, x, y).x / float(fb.sampleCount(x, y)));
        EXPECT_NEAR(fb.colour(x, y).x, want, 4.0f * se + 0.002f * want);
        ++inside;
      } else if (minAngle > 0.46f) {
        EXPECT_EQ(fb.colour(x, y).x, 0.0f);
        ++outside;
      }
    }
  EXPECT_GT(inside, 10);
  EXPECT_GT(outside, 10);
}

}  // namespace
}  // namespace tsr::embree::test
