// Direct light from an area lamp at oblique angles equals the radiance
// integral over the lamp (constant radiance, cosines at both ends, 1/r^2),
// whichever way the lamp and the lit surface face: a lamp facing up under
// a ceiling facing down (the quality suite's indirectly lit room) as well
// as a lamp facing down over a floor.
#include "test_scenes.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

namespace tsr::embree::test {
namespace {

constexpr float kAlbedo = 0.73f, kRadiance = 70.0f;

struct Placement {
  float surfaceY, lampY;  // the lit plane and the lamp's plane
  glm::vec3 target;       // the point on the lit plane the camera looks at
  glm::vec3 eye;
};

// Radiance leaving `p` (on a plane of normal `n`) towards anywhere, by
// quadrature over the 0.6 m square lamp centred at (0, lampY, -0.6) whose
// normal is `lampNormal`.
double integral(const glm::vec3& p, const glm::vec3& n, float lampY, const glm::vec3& lampNormal) {
  constexpr int kSteps = 400;
  double e = 0.0;
  const double cell = 0.6 / kSteps;
  for (int i = 0; i < kSteps; ++i)
    for (int j = 0; j < kSteps; ++j) {
      const glm::dvec3 q(-0.3 + (i + 0.5) * cell, lampY, -0.9 + (j + 0.5) * cell);
      const glm::dvec3 v = q - glm::dvec3(p);
      const double r2 = glm::dot(v, v), r = std::sqrt(r2);
      const double cosSurface = glm::dot(v, glm::dvec3(n)) / r, cosLamp = -glm::dot(v, glm::dvec3(lampNormal)) / r;
      if (cosSurface > 0 && cosLamp > 0) e += kRadiance * cosSurface * cosLamp / r2 * cell * cell;
    }
  return kAlbedo / 3.14159265358979 * e;
}

double rendered(const Placement& s) {
  Scene scene(sharedDevice());
  Material white;
  white.baseColor = glm::vec3(kAlbedo);
  const float y = s.surfaceY;
  const bool ceiling = s.surfaceY > s.lampY;
  // Counter-clockwise seen from the side the surface faces.
  MeshData plane = ceiling ? quad({-2.5f, y, -2.5f}, {2.5f, y, -2.5f}, {2.5f, y, 2.5f}, {-2.5f, y, 2.5f})
                           : quad({-2.5f, y, 2.5f}, {2.5f, y, 2.5f}, {2.5f, y, -2.5f}, {-2.5f, y, -2.5f});
  scene.addInstance(scene.addMesh(plane), scene.addMaterial(white), glm::mat4(1.0f));
  Material lamp;
  lamp.baseColor = glm::vec3(0.05f);
  lamp.emission = glm::vec3(kRadiance);
  const float l = s.lampY;
  MeshData panel = ceiling ? quad({-0.3f, l, -0.3f}, {0.3f, l, -0.3f}, {0.3f, l, -0.9f}, {-0.3f, l, -0.9f})
                           : quad({-0.3f, l, -0.9f}, {0.3f, l, -0.9f}, {0.3f, l, -0.3f}, {-0.3f, l, -0.3f});
  scene.addInstance(scene.addMesh(panel), scene.addMaterial(lamp), glm::mat4(1.0f));
  RenderSettings settings;
  settings.maxDepth = 1;
  settings.samplesPerPass = 256;
  Renderer renderer(settings);
  FrameBuffer fb(4, 4);
  const Camera cam = Camera::lookAt(s.eye, s.target, {0, 1, 0}, glm::radians(0.2f), 1.0f);
  render(renderer, scene, cam, Region::full(4, 4), fb, 1);
  return meanColour(fb).x;
}

TEST(ObliqueLight, ALampFacingUpLightsTheCeilingAsTheIntegralSays) {
  for (const glm::vec3 target : {glm::vec3(0.0f, 3.0f, -1.07f), glm::vec3(-0.76f, 3.0f, -1.34f)}) {
    const Placement s{3.0f, 2.5f, target, {0.0f, 1.4f, 2.4f}};
    const double expected = integral(target, {0, -1, 0}, 2.5f, {0, 1, 0});
    EXPECT_NEAR(rendered(s), expected, 0.05 * expected) << "ceiling point " << target.x << ", " << target.z;
  }
}

TEST(ObliqueLight, ALampFacingDownLightsTheFloorAsTheIntegralSays) {
  for (const glm::vec3 target : {glm::vec3(0.0f, 0.0f, -1.07f), glm::vec3(-0.76f, 0.0f, -1.34f)}) {
    const Placement s{0.0f, 0.5f, target, {0.0f, 1.6f, 2.4f}};
    const double expected = integral(target, {0, 1, 0}, 0.5f, {0, -1, 0});
    EXPECT_NEAR(rendered(s), expected, 0.05 * expected) << "floor point " << target.x << ", " << target.z;
  }
}
}  // namespace
}  // namespace tsr::embree::test
