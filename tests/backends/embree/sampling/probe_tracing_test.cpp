// The irradiance volume's probes as the path tracer fills them
// (tsr/embree/probe_tracing.hpp).
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "test_scenes.hpp"
#include "tsr/embree/probe_tracing.hpp"

using namespace tsr::embree;
using tsr::backend::IrradianceVolume;

namespace {

// Probes over [lo, hi], each traced with `paths` paths in one call.
IrradianceVolume traced(Scene& scene, const glm::vec3& lo, const glm::vec3& hi, std::uint32_t paths) {
  IrradianceVolume v = IrradianceVolume::over(lo, hi, 8);
  std::vector<ProbeSums> sums(v.probeCount());
  traceProbes(scene, RenderSettings{}, v, sums, 0, v.probeCount(), paths);
  return v;
}
}  // namespace

TEST(ProbeTracing, ConstantEnvironmentGivesPiTimesItsRadiance) {
  // A small black box far below: the probes see the environment all round.
  Scene scene(test::sharedDevice());
  Material black;
  black.baseColor = glm::vec3(0.0f);
  scene.addInstance(scene.addMesh(test::box({-0.01f, -50.0f, -0.01f}, {0.01f, -49.99f, 0.01f})),
                    scene.addMaterial(black), glm::mat4(1.0f));
  scene.setEnvironment(Environment::constant(glm::vec3(0.25f, 0.5f, 1.0f)));
  const IrradianceVolume v = traced(scene, {-1, -1, -1}, {1, 1, 1}, 256);
  for (std::size_t p = 0; p < v.probeCount(); ++p) {
    EXPECT_EQ(v.weight(p), 1.0f);
    for (const glm::vec3 n : {glm::vec3(0, 1, 0), glm::vec3(1, 0, 0), glm::vec3(0, 0, -1)}) {
      const glm::vec3 e = v.irradianceAt(p, n);
      EXPECT_NEAR(e.x, kPi * 0.25f, 0.02f);
      EXPECT_NEAR(e.z, kPi * 1.0f, 0.08f);
    }
  }
}

TEST(ProbeTracing, FloorUnderALampLightsUpwardAndHidesTheLampItself) {
  // Grey floor under an emissive panel, black sky. Facing down, a probe
  // gathers the lit floor's bounce; facing up, it would see the lamp, which
  // it leaves out (the reader lights with the lamp directly), and the sky.
  Scene scene(test::sharedDevice());
  test::floorUnderLamp(scene);
  const IrradianceVolume v = traced(scene, {-1, 1, -1}, {1, 2, 1}, 512);
  for (std::size_t p = 0; p < v.probeCount(); ++p) {
    const float facingFloor = v.irradianceAt(p, {0, -1, 0}).x;
    const float facingLamp = v.irradianceAt(p, {0, 1, 0}).x;
    EXPECT_GT(facingFloor, 0.05f) << "the floor's bounce arrives from below";
    EXPECT_LT(facingLamp, 0.25f * facingFloor) << "the lamp seen straight is the reader's light, not the probe's";
  }
}

TEST(ProbeTracing, ALampSeenInAMirrorIsKept) {
  // A mirror floor under the lamp: looking down, a probe sees the lamp's
  // image, light the reader cannot make from its lamps (a caustic), so it
  // stays in the probe; the lamp seen straight is still left out.
  Scene scene(test::sharedDevice());
  Material mirror;
  mirror.type = MaterialType::Mirror;
  mirror.baseColor = glm::vec3(1.0f);
  scene.addInstance(scene.addMesh(test::quad({-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, {-5, 0, -5})),
                    scene.addMaterial(mirror), glm::mat4(1.0f));
  Material lamp;
  lamp.baseColor = glm::vec3(0.0f);
  lamp.emission = glm::vec3(20.0f);
  scene.addInstance(scene.addMesh(test::quad({-1, 5, -1}, {1, 5, -1}, {1, 5, 1}, {-1, 5, 1})), scene.addMaterial(lamp),
                    glm::mat4(1.0f));
  const IrradianceVolume v = traced(scene, {-1, 1, -1}, {1, 2, 1}, 4096);
  float below = 0.0f, expected = 0.0f;
  for (std::size_t p = 0; p < v.probeCount(); ++p) {
    below += v.irradianceAt(p, {0, -1, 0}).x;
    EXPECT_LT(v.irradianceAt(p, {0, 1, 0}).x, 0.05f) << "the lamp seen straight is the reader's light";
    // The lamp's image, 2x2 at y = -5, seen from the probe: L A cos cos / r^2.
    const glm::vec3 to = glm::vec3(0.0f, -5.0f, 0.0f) - v.probePosition(p);
    const float cosine = -to.y / glm::length(to);
    expected += 20.0f * 4.0f * cosine * cosine / glm::dot(to, to);
  }
  EXPECT_NEAR(below / expected, 1.0f, 0.2f) << below << " against " << expected;
}

TEST(ProbeTracing, ProbesInsideGeometryAreWeightedOutAndDistancesAreMeasured) {
  Scene scene(test::sharedDevice());
  Material white;
  scene.addInstance(scene.addMesh(test::box({-1, -1, -1}, {1, 1, 1})), scene.addMaterial(white), glm::mat4(1.0f));
  scene.setEnvironment(Environment::constant(glm::vec3(1.0f)));
  // A grid over a box around the cube: its eight probes stand at (+-1.1 ...),
  // outside; a grid inside the cube: all eight inside.
  const IrradianceVolume outside = traced(scene, {-2, -2, -2}, {2, 2, 2}, 64);
  const IrradianceVolume inside = traced(scene, {-0.8f, -0.8f, -0.8f}, {0.8f, 0.8f, 0.8f}, 64);
  for (std::size_t p = 0; p < 8; ++p) {
    EXPECT_EQ(outside.weight(p), 1.0f);
    EXPECT_EQ(inside.weight(p), 0.0f);
    // Towards the cube's centre the first hit is the cube's near face.
    const glm::vec3 at = outside.probePosition(p);
    const glm::vec3 towards = glm::normalize(-at);
    const glm::vec2 texel = tsr::backend::equalAreaSphereToSquare(towards) * float(IrradianceVolume::kDistanceSide);
    const std::size_t t = std::size_t(texel.y) * IrradianceVolume::kDistanceSide + std::size_t(texel.x);
    const float mean = outside.distance[p * IrradianceVolume::kDistanceTexels + t].x;
    // The nearest corner of the cube is |at| - sqrt(3) away along the
    // diagonal; the texel's directions spread round it.
    EXPECT_GT(mean, glm::length(at) - 1.8f);
    EXPECT_LT(mean, glm::length(at));
  }
}

TEST(ProbeTracing, TurnsAddUpToOneCallWhateverTheSplit) {
  // The same probes traced in one call or in turns of any size (as a node
  // and the client, or two nodes, might) are bitwise the same.
  Scene scene(test::sharedDevice());
  test::floorUnderLamp(scene);
  IrradianceVolume whole = IrradianceVolume::over({-1, 1, -1}, {1, 2, 1}, 8);
  IrradianceVolume split = whole;
  std::vector<ProbeSums> wholeSums(8), splitSums(8);
  traceProbes(scene, RenderSettings{}, whole, wholeSums, 0, 8, 128);
  traceProbes(scene, RenderSettings{}, whole, wholeSums, 0, 8, 128);
  traceProbes(scene, RenderSettings{}, split, splitSums, 5, 3, 128);  // wraps: 5, 6, 7
  traceProbes(scene, RenderSettings{}, split, splitSums, 0, 5, 256);  // 0..4 in one turn of two rounds
  traceProbes(scene, RenderSettings{}, split, splitSums, 5, 3, 128);
  EXPECT_EQ(whole.irradiance, split.irradiance);
  EXPECT_EQ(whole.distance, split.distance);
  EXPECT_GT(split.version, 0u);
}
