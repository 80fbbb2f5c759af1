#include "test_scenes.hpp"

#include <gtest/gtest.h>

namespace tsr::embree::test {
namespace {

constexpr float kHeight = 1.0f;  // light above the floor
constexpr float kHalf = 0.5f;    // light half-size
constexpr float kLe = 3.0f;
constexpr float kAlbedo = 0.7f;
constexpr std::uint32_t kSize = 24;

// Camera between floor and light, looking straight down.
const glm::vec3 kEye{0.0f, 0.5f, 0.0f};
const Camera kCamera = Camera::lookAt(kEye, {0, 0, 0}, {0, 0, -1}, glm::radians(90.0f), 1.0f);

FrameBuffer renderUnderLight(const Material& floor, LightSampling mode, int passes) {
  Scene scene(sharedDevice());
  scene.addInstance(scene.addMesh(quad({-20, 0, 20}, {20, 0, 20}, {20, 0, -20}, {-20, 0, -20})),
                    scene.addMaterial(floor), glm::mat4(1.0f));
  Material lamp;
  lamp.baseColor = glm::vec3(0.0f);
  lamp.emission = glm::vec3(kLe);
  // Wound to face down.
  scene.addInstance(scene.addMesh(quad({-kHalf, kHeight, -kHalf}, {kHalf, kHeight, -kHalf}, {kHalf, kHeight, kHalf},
                                       {-kHalf, kHeight, kHalf})),
                    scene.addMaterial(lamp), glm::mat4(1.0f));
  RenderSettings s;
  s.maxDepth = 1;
  s.samplesPerPass = 16;
  s.lightSampling = mode;
  Renderer renderer(s);
  FrameBuffer fb(kSize, kSize);
  render(renderer, scene, kCamera, Region::full(kSize, kSize), fb, passes);
  return fb;
}

// Form factor from a floor point to an axis-aligned rectangle parallel to it
// at height h, one corner straight above the point (a, b >= 0).
double cornerFactor(double a, double b, double h) {
  double x = a / h, y = b / h;
  double sx = std::sqrt(1 + x * x), sy = std::sqrt(1 + y * y);
  return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2 * std::numbers::pi);
}
double signedCorner(double a, double b, double h) {
  return (a < 0 ? -1 : 1) * (b < 0 ? -1 : 1) * cornerFactor(std::abs(a), std::abs(b), h);
}
double formFactor(double px, double pz) {
  double x0 = -kHalf - px, x1 = kHalf - px, z0 = -kHalf - pz, z1 = kHalf - pz;
  return signedCorner(x1, z1, kHeight) - signedCorner(x0, z1, kHeight) - signedCorner(x1, z0, kHeight) +
         signedCorner(x0, z0, kHeight);
}

double analyticMean() {
  glm::mat3 rot(kCamera.cameraToWorld);
  double sum = 0.0;
  for (std::uint32_t py = 0; py < kSize; ++py)
    for (std::uint32_t px = 0; px < kSize; ++px)
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
          float cx = kCamera.left + (kCamera.right - kCamera.left) * ((float(px) + (i + 0.5f) / 4) / kSize);
          float cy = kCamera.top - (kCamera.top - kCamera.bottom) * ((float(py) + (j + 0.5f) / 4) / kSize);
          glm::vec3 d = rot * glm::vec3(cx, cy, -kCamera.near);  // the window lies on the near plane
          glm::vec3 p = kEye + d * (-kEye.y / d.y);
          sum += kAlbedo * kLe * formFactor(p.x, p.z);
        }
  return sum / (kSize * kSize * 16.0);
}

TEST(EmbreeAreaLight, AllStrategiesMatchAnalyticFormFactor) {
  Material floor;
  floor.baseColor = glm::vec3(kAlbedo);
  double want = analyticMean();
  ASSERT_GT(want, 0.1);
  for (LightSampling mode : {LightSampling::Mis, LightSampling::LightOnly, LightSampling::BsdfOnly}) {
    FrameBuffer fb = renderUnderLight(floor, mode, 4);
    float got = meanColour(fb).x;
    float se = meanStandardError(fb);
    EXPECT_NEAR(got, want, 4.0 * se + 0.005 * want) << "mode " << int(mode) << " se " << se;
  }
}

// No closed form for GGX: the three estimators must agree within noise,
// which checks that sampling, evaluation and pdf are mutually consistent.
TEST(EmbreeAreaLight, GgxStrategiesAgree) {
  // The fixed classes, then glTF metallic-roughness as metal, as a
  // dielectric layer over diffuse, and half and half.
  for (int k = 0; k < 5; ++k) {
    const MaterialType type = k == 0   ? MaterialType::Conductor
                              : k == 1 ? MaterialType::Dielectric
                                       : MaterialType::MetallicRoughness;
    Material floor;
    floor.type = type;
    floor.baseColor = glm::vec3(0.9f);
    floor.roughness = 0.5f;
    floor.metallic = k == 2 ? 1.0f : k == 3 ? 0.0f : 0.5f;
    FrameBuffer mis = renderUnderLight(floor, LightSampling::Mis, 4);
    FrameBuffer light = renderUnderLight(floor, LightSampling::LightOnly, 4);
    FrameBuffer bsdf = renderUnderLight(floor, LightSampling::BsdfOnly, 8);
    float m = meanColour(mis).x, l = meanColour(light).x, b = meanColour(bsdf).x;
    float sm = meanStandardError(mis), sl = meanStandardError(light), sb = meanStandardError(bsdf);
    ASSERT_GT(m, 0.01f);
    EXPECT_NEAR(m, l, 4.0f * std::hypot(sm, sl) + 0.005f * m) << "case " << k;
    EXPECT_NEAR(m, b, 4.0f * std::hypot(sm, sb) + 0.005f * m) << "case " << k;
    // MIS should not be noisier than the worse single strategy.
    EXPECT_LE(sm, std::max(sl, sb * std::sqrt(2.0f)));
  }
}

}  // namespace
}  // namespace tsr::embree::test
