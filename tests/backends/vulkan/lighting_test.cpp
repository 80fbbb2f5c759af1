#include "test_util.hpp"

#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace tsr::vk {
namespace {

using test::device;

constexpr float kPi = std::numbers::pi_v<float>;

// Lambertian quad in z = 0 under a point light: every pixel must equal
// albedo / pi * I * cos(theta) / r^2 at the surface point it sees.
TEST(VulkanLighting, PointLightOnDiffuseQuadMatchesAnalytic) {
  Scene scene(device());
  MeshId quad = scene.addMesh(test::quad({-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}));
  Material mat;
  mat.baseColor = {0.5f, 0.25f, 0.75f};
  scene.addInstance(quad, scene.addMaterial(mat), glm::mat4(1.0f));
  const glm::vec3 lightPos(0.3f, 0.2f, 1.0f);
  const glm::vec3 intensity(10.0f, 20.0f, 5.0f);
  scene.addLight(PointLight{lightPos, intensity});

  const Camera cam = Camera::lookAt({0, 0.5f, 3}, {0, 0, 0}, {0, 1, 0}, 0.9f, 1.0f);
  const Region full = Region::full(64, 64);
  FrameBuffer fb(64, 64);
  Renderer renderer(device(), {.msaaSamples = 1});
  renderer.render(scene, cam, full, fb);
  test::writePng("/tmp/tsr_vk_point_light.png", fb, 0.5f);

  int checked = 0;
  for (int py = 4; py < 64; py += 9)
    for (int px = 3; px < 64; px += 9) {
      glm::vec3 p = test::pixelOnPlane(cam, full, px, py, {0, 0, 1}, 0.0f);
      if (std::abs(p.x) > 1.9f || std::abs(p.y) > 1.9f) continue;
      glm::vec3 d = lightPos - p;
      float r2 = glm::dot(d, d);
      float cosTheta = d.z / std::sqrt(r2);
      glm::vec3 expected = mat.baseColor / kPi * intensity * cosTheta / r2;
      glm::vec4 got = fb.colour(px, py);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 0.01f * expected[c]) << px << "," << py;
      EXPECT_FLOAT_EQ(got.a, 1.0f);
      ++checked;
    }
  EXPECT_GT(checked, 20);
}

// Depth is camera-space distance along the view axis, as in the Embree back-end.
TEST(VulkanLighting, DepthIsCameraSpaceDistanceAlongViewAxis) {
  Scene scene(device());
  MeshId quad = scene.addMesh(test::quad({-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}));
  scene.addInstance(quad, scene.addMaterial({}), glm::mat4(1.0f));
  Camera cam = Camera::lookAt({0.5f, 1.5f, 3}, {0, 0, 0}, {0, 1, 0}, 1.6f, 1.5f, 0.05f, 50.0f);
  const Region full = Region::full(96, 64);
  FrameBuffer fb(96, 64);
  Renderer renderer(device());
  renderer.render(scene, cam, full, fb);

  const glm::vec3 org(cam.cameraToWorld[3]);
  const glm::vec3 forward = -glm::vec3(cam.cameraToWorld[2]);
  int hits = 0, misses = 0;
  for (int py = 1; py < 64; py += 5)
    for (int px = 2; px < 96; px += 7) {
      glm::vec3 p = test::pixelOnPlane(cam, full, px, py, {0, 0, 1}, 0.0f);
      float depth = fb.depth(px, py);
      bool inside = std::abs(p.x) < 1.95f && std::abs(p.y) < 1.95f && glm::dot(p - org, forward) > 0.0f;
      bool outside = std::abs(p.x) > 2.05f || std::abs(p.y) > 2.05f;
      if (inside) {
        EXPECT_NEAR(depth, glm::dot(p - org, forward), 1e-4f * glm::dot(p - org, forward)) << px << "," << py;
        ++hits;
      } else if (outside) {
        EXPECT_TRUE(std::isinf(depth)) << px << "," << py << " depth " << depth;
        EXPECT_EQ(fb.colour(px, py), glm::vec4(0.0f));
        ++misses;
      }
    }
  EXPECT_GT(hits, 20);
  EXPECT_GT(misses, 5);
}

TEST(VulkanLighting, DirectionalAndSpotLightsMatchAnalytic) {
  Scene scene(device());
  MeshId quad = scene.addMesh(test::groundQuad(0, 0, 3));
  Material mat;
  mat.baseColor = glm::vec3(0.6f);
  scene.addInstance(quad, scene.addMaterial(mat), glm::mat4(1.0f));
  const glm::vec3 dir = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  scene.addLight(DirectionalLight{dir, glm::vec3(2.0f)});
  SpotLight spot;
  spot.position = {0, 2, 0};
  spot.direction = {0, -1, 0};
  spot.intensity = glm::vec3(8.0f);
  spot.innerAngle = 0.4f;
  spot.outerAngle = 0.6f;
  scene.addLight(spot);
  const Camera cam = Camera::lookAt({0, 4, 4}, {0, 0, 0}, {0, 1, 0}, 0.9f, 1.0f);
  const Region full = Region::full(64, 64);
  FrameBuffer fb(64, 64);
  Renderer renderer(device());
  renderer.render(scene, cam, full, fb);

  int checked = 0;
  for (int py = 2; py < 64; py += 6)
    for (int px = 2; px < 64; px += 6) {
      glm::vec3 p = test::pixelOnPlane(cam, full, px, py, {0, 1, 0}, 0.0f);
      if (std::abs(p.x) > 2.9f || std::abs(p.z) > 2.9f) continue;
      float e = 2.0f * -dir.y;
      glm::vec3 d = spot.position - p;
      float r2 = glm::dot(d, d);
      glm::vec3 wi = d / std::sqrt(r2);
      float c = wi.y;  // cos between the spot axis (0, -1, 0) and the direction light -> p
      float ci = std::cos(spot.innerAngle), co = std::cos(spot.outerAngle);
      float falloff = c >= ci ? 1.0f : c <= co ? 0.0f : glm::smoothstep(co, ci, c);
      float spotE = 8.0f * falloff * wi.y / r2;
      float expected = 0.6f / kPi * (e + spotE);
      // The falloff's steep edge is sensitive to where in the pixel the shader evaluates.
      float tol = (falloff > 0.0f && falloff < 1.0f) ? 0.05f : 0.01f;
      EXPECT_NEAR(fb.colour(px, py).r, expected, tol * expected) << px << "," << py;
      ++checked;
    }
  EXPECT_GT(checked, 40);
}

TEST(VulkanLighting, AmbientFromConstantEnvironmentIsAlbedoTimesRadiance) {
  Scene scene(device());
  MeshId quad = scene.addMesh(test::quad({-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}, false));
  Material mat;
  mat.baseColor = {0.2f, 0.4f, 0.8f};
  scene.addInstance(quad, scene.addMaterial(mat), glm::mat4(1.0f));
  scene.setEnvironment(Environment::constant({0.5f, 1.0f, 2.0f}));
  const Camera cam = Camera::lookAt({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 0.9f, 1.0f);
  FrameBuffer fb(32, 32);
  Renderer renderer(device());
  renderer.render(scene, cam, Region::full(32, 32), fb);
  EXPECT_NEAR(fb.colour(16, 16).r, 0.1f, 1e-5f);
  EXPECT_NEAR(fb.colour(16, 16).g, 0.4f, 1e-5f);
  EXPECT_NEAR(fb.colour(16, 16).b, 1.6f, 1e-5f);
}

// Emission leaves the counter-clockwise (front) face only, as in the path tracer.
TEST(VulkanLighting, EmissionOnlyFromFrontFace) {
  Scene scene(device());
  Material glow;
  glow.baseColor = glm::vec3(0.0f);
  glow.emission = {1.0f, 2.0f, 3.0f};
  MaterialId m = scene.addMaterial(glow);
  // Left quad faces the camera (+Z), right quad faces away.
  scene.addInstance(scene.addMesh(test::quad({-2, -1, 0}, {-0.5f, -1, 0}, {-0.5f, 1, 0}, {-2, 1, 0})), m,
                    glm::mat4(1.0f));
  scene.addInstance(scene.addMesh(test::quad({2, -1, 0}, {0.5f, -1, 0}, {0.5f, 1, 0}, {2, 1, 0})), m, glm::mat4(1.0f));
  const Camera cam = Camera::lookAt({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 1.2f, 1.0f);
  const Region full = Region::full(64, 64);
  FrameBuffer fb(64, 64);
  Renderer renderer(device());
  renderer.render(scene, cam, full, fb);
  glm::vec2 left = test::project(cam, full, {-1.25f, 0, 0});
  glm::vec2 right = test::project(cam, full, {1.25f, 0, 0});
  EXPECT_EQ(fb.colour(int(left.x), int(left.y)), glm::vec4(1.0f, 2.0f, 3.0f, 1.0f));
  EXPECT_EQ(fb.colour(int(right.x), int(right.y)), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  EXPECT_FALSE(std::isinf(fb.depth(int(right.x), int(right.y))));
}

TEST(VulkanLighting, SameInputsGiveIdenticalPixels) {
  Scene scene(device());
  MeshId sphere = scene.addMesh(test::uvSphere(16, 24));
  Material a;
  a.type = MaterialType::Conductor;
  a.baseColor = {0.9f, 0.6f, 0.3f};
  a.roughness = 0.4f;
  scene.addInstance(sphere, scene.addMaterial(a), glm::mat4(1.0f));
  scene.addLight(PointLight{{2, 2, 2}, glm::vec3(20.0f)});
  scene.addLight(DirectionalLight{{-1, -1, -1}, glm::vec3(1.0f)});
  const Camera cam = Camera::lookAt({0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 0.8f, 1.0f);
  Renderer renderer(device(), {.msaaSamples = 4});
  FrameBuffer a1(48, 48), a2(48, 48);
  renderer.render(scene, cam, Region::full(48, 48), a1);
  renderer.render(scene, cam, Region::full(48, 48), a2);
  EXPECT_EQ(a1.colourImage(), a2.colourImage());
  EXPECT_EQ(a1.depthImage(), a2.depthImage());
}

}  // namespace
}  // namespace tsr::vk
