// Participating media in the path tracer, checked against what is known
// exactly (pbrt-v4's media tests check the same properties): the
// Henyey–Greenstein phase function is a density with mean cosine g and
// is sampled by it; a purely absorbing slab passes exp(-sigma_a d); a
// purely emitting one adds emission x depth; an index-matched sphere of
// white scattering medium in a white furnace neither gains nor loses
// light; and media render bitwise alike on one thread and two.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "test_scenes.hpp"
#include "tsr/embree/phase_function.hpp"
#include "tsr/embree/rng.hpp"

namespace tsr::embree::test {
namespace {

float integrate(float g, int power) {  // over the sphere: integral of cos^power * p(cos)
  const int n = 200000;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double c = -1.0 + 2.0 * (i + 0.5) / n;
    sum += std::pow(c, power) * henyeyGreenstein(float(c), g) * 2.0 * kPi * (2.0 / n);
  }
  return float(sum);
}

TEST(EmbreeMedia, HenyeyGreensteinIsADensityWithMeanCosineG) {
  for (float g : {-0.7f, 0.0f, 0.3f, 0.9f}) {
    EXPECT_NEAR(integrate(g, 0), 1.0f, 2e-3f) << g;
    EXPECT_NEAR(integrate(g, 1), g, 2e-3f) << g;
  }
}

TEST(EmbreeMedia, HenyeyGreensteinSamplesFollowTheirDensity) {
  const glm::vec3 in = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
  for (float g : {-0.7f, 0.0f, 0.3f, 0.9f}) {
    constexpr int kBins = 20, kSamples = 200000;
    std::array<int, kBins> seen{};
    Rng rng(7, 11);
    for (int i = 0; i < kSamples; ++i) {
      const glm::vec3 out = sampleHenyeyGreenstein(in, g, rng.uniform2());
      ASSERT_NEAR(glm::length(out), 1.0f, 1e-4f);
      const float c = glm::dot(in, out);
      ++seen[std::min(kBins - 1, int((c + 1.0f) * 0.5f * kBins))];
    }
    double chi2 = 0;
    for (int b = 0; b < kBins; ++b) {
      double expected = 0;  // the density over the bin, by quadrature
      for (int k = 0; k < 100; ++k) {
        const double c = -1.0 + 2.0 * (b + (k + 0.5) / 100.0) / kBins;
        expected += henyeyGreenstein(float(c), g) * 2.0 * kPi * (2.0 / kBins / 100.0);
      }
      expected *= kSamples;
      if (expected > 5) chi2 += (seen[b] - expected) * (seen[b] - expected) / expected;
    }
    EXPECT_LT(chi2, 45.0) << "g " << g << ": 19 degrees of freedom, p < 0.001 beyond 43.8";
  }
}

struct SlabView {
  Scene scene{sharedDevice()};
  // Narrow: every ray crosses the slab within 0.01 % of square-on.
  Camera camera = Camera::lookAt({0, 0, 6}, {0, 0, 0}, {0, 1, 0}, glm::radians(1.0f), 1.0f);
};

// A 2-unit slab (z from -1 to 1, wide enough to fill the view) of `medium`
// with no surface, in front of a constant environment.
glm::vec3 throughSlab(const Medium& medium, const glm::vec3& sky, int passes, int threads = 0,
                      FrameBuffer* out = nullptr) {
  SlabView v;
  Material boundary;
  boundary.type = MaterialType::Interface;
  boundary.interior = medium;
  v.scene.addInstance(v.scene.addMesh(box({-5, -5, -1}, {5, 5, 1})), v.scene.addMaterial(boundary), glm::mat4(1.0f));
  v.scene.setEnvironment(Environment::constant(sky));
  RenderSettings s;
  s.samplesPerPass = 16;
  s.threads = threads;
  Renderer renderer(s);
  FrameBuffer fb(16, 16);
  render(renderer, v.scene, v.camera, Region::full(16, 16), fb, passes);
  if (out) *out = fb;
  return meanColour(fb);
}

TEST(EmbreeMedia, AnAbsorbingSlabPassesExpOfMinusSigmaTimesDepth) {
  Medium m;
  m.absorption = {0.5f, 0.25f, 1.0f};
  const glm::vec3 c = throughSlab(m, glm::vec3(1.0f), 32);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], std::exp(-2.0f * m.absorption[k]), 0.01f) << k;
}

TEST(EmbreeMedia, AnEmittingSlabAddsEmissionTimesDepth) {
  Medium m;
  m.emission = {0.25f, 0.5f, 0.1f};
  const glm::vec3 c = throughSlab(m, glm::vec3(0.0f), 1);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], 2.0f * m.emission[k], 1e-4f) << k;
  // Absorption within: e (1 - exp(-sigma d)) / sigma.
  m.absorption = glm::vec3(0.5f);
  const glm::vec3 d = throughSlab(m, glm::vec3(0.0f), 1);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(d[k], m.emission[k] * (1.0f - std::exp(-1.0f)) / 0.5f, 1e-4f) << k;
}

TEST(EmbreeMedia, AWhiteScatteringSphereInAWhiteFurnaceNeitherGainsNorLoses) {
  Scene scene(sharedDevice());
  Medium white;
  white.scattering = glm::vec3(2.0f);
  white.g = 0.6f;
  const glm::vec3 c = furnaceMean(scene, white);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], 0.5f, 0.005f) << k;  // 1 %
}

// Light reaching points in a medium is found two ways, by light sampling
// through the phase function and by phase sampling that hits the lamp;
// each alone and both weighted (MIS) must agree, with scene fog and with
// a scattering box on the floor under the lamp.
glm::vec3 foggyLamp(LightSampling mode, int passes) {
  Scene scene(sharedDevice());
  floorUnderLamp(scene);
  Material boundary;
  boundary.type = MaterialType::Interface;
  Medium block;
  block.scattering = {0.8f, 0.6f, 0.4f};
  block.absorption = glm::vec3(0.1f);
  block.g = -0.3f;
  boundary.interior = block;
  scene.addInstance(scene.addMesh(box({-1, 0, -1}, {1, 2, 1})), scene.addMaterial(boundary), glm::mat4(1.0f));
  Medium haze;
  haze.scattering = glm::vec3(0.05f);
  haze.g = 0.5f;
  scene.setEnvironment(Environment().withMedium(haze));
  RenderSettings s;
  s.maxDepth = 6;
  s.samplesPerPass = 16;
  s.lightSampling = mode;
  Renderer renderer(s);
  Camera camera = Camera::lookAt({0, 2, 7}, {0, 1, 0}, {0, 1, 0}, glm::radians(40.0f), 1.0f);
  FrameBuffer fb(24, 24);
  render(renderer, scene, camera, Region::full(24, 24), fb, passes);
  return meanColour(fb);
}

TEST(EmbreeMedia, LightSamplingPhaseSamplingAndTheirMixAgree) {
  const glm::vec3 mis = foggyLamp(LightSampling::Mis, 16);
  const glm::vec3 light = foggyLamp(LightSampling::LightOnly, 16);
  const glm::vec3 phase = foggyLamp(LightSampling::BsdfOnly, 64);
  for (int k = 0; k < 3; ++k) {
    EXPECT_GT(mis[k], 0.01f) << k;
    EXPECT_NEAR(light[k], mis[k], 0.03f * mis[k]) << k;
    EXPECT_NEAR(phase[k], mis[k], 0.05f * mis[k]) << k;
  }
}

// A small lamp or a point light in haze, seen through it: with MIS, light
// scattered along each camera ray is also sampled at distances drawn
// towards the lights (equiangular sampling). The image agrees with light
// sampling alone (where the equiangular technique is off), and around the
// point light, where free flights rarely stop, it is far less noisy.
constexpr int kAreaLamp = 1, kPointLight = 2;

glm::vec3 hazeAroundLamps(LightSampling mode, float* error, int lights, int passes) {
  Scene scene(sharedDevice());
  Material floor;
  floor.baseColor = glm::vec3(0.4f);
  scene.addInstance(scene.addMesh(quad({-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, {-5, 0, -5})), scene.addMaterial(floor),
                    glm::mat4(1.0f));
  Material lamp;
  lamp.baseColor = glm::vec3(0.0f);
  lamp.emission = glm::vec3(200.0f);
  if (lights & kAreaLamp)
    scene.addInstance(scene.addMesh(quad({-1.6f, 2, -0.1f}, {-1.4f, 2, -0.1f}, {-1.4f, 2, 0.1f}, {-1.6f, 2, 0.1f})),
                      scene.addMaterial(lamp), glm::mat4(1.0f));
  if (lights & kPointLight) scene.addLight(PointLight{{1.5f, 1.5f, 0.0f}, glm::vec3(3.0f)});
  Medium haze;
  haze.scattering = glm::vec3(0.15f);
  haze.absorption = glm::vec3(0.02f);
  haze.g = 0.3f;
  scene.setEnvironment(Environment().withMedium(haze));
  RenderSettings s;
  s.maxDepth = 3;
  s.samplesPerPass = 64;
  s.lightSampling = mode;
  Renderer renderer(s);
  const Camera camera = Camera::lookAt({0, 1.5f, 5}, {0, 1, 0}, {0, 1, 0}, glm::radians(60.0f), 1.0f);
  FrameBuffer fb(24, 24);
  render(renderer, scene, camera, Region::full(24, 24), fb, passes);
  *error = meanStandardError(fb);
  return meanColour(fb);
}

TEST(EmbreeMedia, EquiangularSamplingAgreesAndLowersTheNoiseAroundLamps) {
  for (const int lights : {kAreaLamp, kPointLight}) {
    float misError = 0.0f, lightError = 0.0f;
    const glm::vec3 mis = hazeAroundLamps(LightSampling::Mis, &misError, lights, 16);
    const glm::vec3 light = hazeAroundLamps(LightSampling::LightOnly, &lightError, lights, 16);
    EXPECT_GT(luminance(mis), 0.01f);
    EXPECT_NEAR(luminance(light), luminance(mis), 4.0f * std::hypot(misError, lightError))
        << (lights == kAreaLamp ? "area lamp" : "point light");
    if (lights == kPointLight) {
      EXPECT_LT(misError, 0.6f * lightError) << misError << " against " << lightError;
    }
  }
}

TEST(EmbreeMedia, MediaRenderBitwiseAlikeOnOneThreadAndTwo) {
  Medium fog;
  fog.absorption = glm::vec3(0.1f);
  fog.scattering = {0.4f, 0.5f, 0.6f};
  fog.emission = glm::vec3(0.05f);
  fog.g = 0.3f;
  FrameBuffer one(16, 16), two(16, 16);
  throughSlab(fog, glm::vec3(0.8f), 2, 1, &one);
  throughSlab(fog, glm::vec3(0.8f), 2, 2, &two);
  EXPECT_TRUE(identical(one, two));
}

}  // namespace
}  // namespace tsr::embree::test
