// Spatio-temporal photon density estimation: the validity test, the
// reconstruction's error, the lookup's continuity, determinism, and the
// energy that reaches the image.
#include "test_scenes.hpp"

#include "tsr/embree/error.hpp"
#include "tsr/embree/photon_sequence.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace tsr::embree {
namespace {

using test::sharedDevice;

constexpr float kLight = 100000.0f;  // the Cornell box's point light

PhotonSettings smallSettings() {
  PhotonSettings s;
  s.elementSize = 70.0f;  // about 8 x 8 elements per wall quad
  s.photonsPerFrame = 20000;
  s.tMax = 9;
  s.accuracy = 0.1f;
  return s;
}

// Adds frames [0, frames) to seq, letting `pose` edit the scene first.
void addFrames(PhotonSequence& seq, Scene& scene, int frames, const std::function<void(int)>& pose = {}) {
  for (int f = 0; f < frames; ++f) {
    if (pose) pose(f);
    seq.addFrame(scene, f);
  }
}

// Area is not exposed; elements of a uniform subdivision are near equal, so
// the plain mean over elements is the error measure.
double relativeError(const std::vector<glm::vec3>& x, const std::vector<glm::vec3>& ref) {
  double num = 0.0, den = 0.0;
  for (std::size_t e = 0; e < x.size(); ++e) {
    const double d = luminance(x[e]) - luminance(ref[e]);
    num += d * d;
    den += double(luminance(ref[e])) * luminance(ref[e]);
  }
  return num / den;
}

std::vector<glm::vec3> fieldValues(const IrradianceField& f) {
  std::vector<glm::vec3> v(f.elementCount());
  for (std::size_t e = 0; e < v.size(); ++e) v[e] = f.element(e);
  return v;
}

struct Extents {
  double fullForward = 0.0, fullBackward = 0.0, pastStep = 0.0;
  std::size_t elements = 0;
};

// Extents of the elements that collect at least `minCount` photons a frame
// at the centre frame, reconstructing frame 4 of frames 0..8.
Extents extents(float stepFactor, int stepFrame, float minCount, float emissionStep = PhotonSettings{}.emissionStep) {
  Scene scene(sharedDevice());
  test::cornellBox(scene, 0);
  PhotonSettings settings = smallSettings();
  settings.emissionStep = emissionStep;
  settings.photonsPerFrame = 60000;  // about 10 photons a frame on a lit element
  PhotonSequence seq(settings);
  addFrames(seq, scene, 9, [&](int f) {
    scene.setLight(LightId{0},
                   PointLight{{213.0f, 300.0f, 227.0f}, glm::vec3(kLight * (f >= stepFrame ? stepFactor : 1.0f))});
  });
  const Reconstruction r = seq.reconstruct(4);
  const std::vector<glm::vec3> raw = seq.rawIrradiance(4);
  const std::vector<glm::vec3> rawPrev = seq.rawIrradiance(3);
  Extents out;
  // Photon counts are not exposed; a well-lit element is one whose raw
  // irradiance in frames 3 and 4 is high relative to the scene's mean.
  double mean = 0.0;
  for (const auto& v : raw) mean += luminance(v);
  mean /= double(raw.size());
  for (std::size_t e = 0; e < raw.size(); ++e) {
    if (luminance(raw[e]) + luminance(rawPrev[e]) < 2.0f * minCount * float(mean)) continue;
    ++out.elements;
    out.fullForward += r.forward[e] == 4;
    out.fullBackward += r.backward[e] == 4;
    out.pastStep += 4 + int(r.forward[e]) >= stepFrame;
  }
  out.fullForward /= double(out.elements);
  out.fullBackward /= double(out.elements);
  out.pastStep /= double(out.elements);
  return out;
}

TEST(EmbreePhotonSequence, ValidityTestRunsThroughAStaticScene) {
  const Extents e = extents(1.0f, 100, 1.0f);
  ASSERT_GT(e.elements, 50u);
  EXPECT_GT(e.fullForward, 0.85);
  EXPECT_GT(e.fullBackward, 0.85);
}

TEST(EmbreePhotonSequence, ValidityTestStopsAtALightStep) {
  // The light gets four times brighter from frame 6 on: collection for
  // frame 4 must stop at frame 5 going forwards, and still run backwards.
  // With the emission rule off, the photon counts' test (002 eq. 1) alone.
  const Extents e = extents(4.0f, 6, 1.0f, 1e6f);
  ASSERT_GT(e.elements, 50u);
  EXPECT_LT(e.pastStep, 0.1);
  EXPECT_GT(e.fullBackward, 0.85);
}

TEST(EmbreePhotonSequence, ALightSwitchEndsTheWindowOfEveryElement) {
  // 30% brighter from frame 6: within the counts' noise on dim elements,
  // but the emitted power is known exactly, so no element, lit or dim,
  // collects past the switch; a static light cuts nothing.
  const Extents step = extents(1.3f, 6, 0.0f);
  ASSERT_GT(step.elements, 100u);
  EXPECT_EQ(step.pastStep, 0.0);
  EXPECT_GT(step.fullBackward, 0.85);
  const Extents counts = extents(1.3f, 6, 0.0f, 1e6f);
  EXPECT_GT(counts.pastStep, 0.2) << "without it, the counts' test lets a small step through on many elements";
  const Extents still = extents(1.0f, 100, 0.0f);
  EXPECT_GT(still.fullForward, 0.85);
}

TEST(EmbreePhotonSequence, ReconstructionOfAStaticSceneBeatsOneFramesCounts) {
  Scene scene(sharedDevice());
  test::cornellBox(scene, 0);
  PhotonSettings ref = smallSettings();
  ref.photonsPerFrame = 1000000;
  ref.tMax = 1;
  PhotonSequence reference(ref);
  reference.addFrame(scene, 0);
  const std::vector<glm::vec3> truth = reference.rawIrradiance(0);

  PhotonSequence seq(smallSettings());
  addFrames(seq, scene, 9);
  const double oneFrame = relativeError(seq.rawIrradiance(4), truth);
  const double reconstructed = relativeError(fieldValues(seq.reconstruct(4).field), truth);
  EXPECT_LT(reconstructed, 0.25 * oneFrame) << "one frame " << oneFrame << ", reconstructed " << reconstructed;

  // Frames add information beyond spatial filtering: a one-frame window is worse.
  PhotonSettings single = smallSettings();
  single.tMax = 1;
  PhotonSequence alone(single);
  alone.addFrame(scene, 4);
  const double spatialOnly = relativeError(fieldValues(alone.reconstruct(4).field), truth);
  EXPECT_LT(reconstructed, spatialOnly) << "spatial only " << spatialOnly << ", space-time " << reconstructed;
}

TEST(EmbreePhotonSequence, IrradianceIsContinuousAcrossElementBorders) {
  Scene scene(sharedDevice());
  test::cornellBox(scene, 0);
  PhotonSequence seq(smallSettings());
  addFrames(seq, scene, 5);
  const IrradianceField field = seq.reconstruct(2).field;
  // Instance 0 holds the floor as triangles 0 (p0 p1 p2) and 1 (p0 p2 p3).
  // Along a line through triangle 0, steps of 1e-4 in barycentrics must not
  // jump, while the element values along it do differ.
  double maxStep = 0.0, elementJump = 0.0, scale = 0.0;
  glm::vec3 prev = field.at(0, 0, 0.0f, 0.3f);
  for (int i = 1; i <= 7000; ++i) {
    const glm::vec3 v = field.at(0, 0, float(i) * 1e-4f, 0.3f);
    maxStep = std::max(maxStep, double(std::abs(luminance(v) - luminance(prev))));
    scale = std::max(scale, double(luminance(v)));
    prev = v;
  }
  for (std::size_t e = 1; e < 64; ++e)
    elementJump =
        std::max(elementJump, double(std::abs(luminance(field.element(e)) - luminance(field.element(e - 1)))));
  ASSERT_GT(scale, 0.0);
  EXPECT_LT(maxStep, 0.01 * scale);
  EXPECT_GT(elementJump, 20.0 * maxStep);
  // Across the quad's diagonal p0-p2: the same point seen from both triangles.
  for (float s : {0.1f, 0.37f, 0.5f, 0.83f}) {
    const glm::vec3 a = field.at(0, 0, 0.0f, s), b = field.at(0, 1, s, 0.0f);
    EXPECT_NEAR(luminance(a), luminance(b), 1e-4 * scale) << "at " << s;
  }
}

TEST(EmbreePhotonSequence, ResultsDoNotDependOnTheThreadCount) {
  auto run = [](int threads) {
    Scene scene(sharedDevice());
    test::cornellBox(scene, 0);
    PhotonSettings s = smallSettings();
    s.threads = threads;
    s.photonsPerFrame = 0;  // through the pilot pass too
    s.pilotPhotons = 10000;
    PhotonSequence seq(s);
    addFrames(seq, scene, 3);
    return fieldValues(seq.reconstruct(1).field);
  };
  const auto one = run(1), two = run(2);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t e = 0; e < one.size(); ++e) ASSERT_EQ(one[e], two[e]) << "element " << e;
}

TEST(EmbreePhotonSequence, RenderedIndirectMatchesPathTracing) {
  // The Cornell box with a point light: every bit of indirect light is
  // diffuse interreflection, so the image's mean Indirect must agree.
  Scene scene(sharedDevice());
  const Camera camera = test::cornellBox(scene, 0);
  const Region region{32, 32, 0, 0, 32, 32};
  PhotonSettings s = smallSettings();
  s.photonsPerFrame = 100000;
  PhotonSequence seq(s);
  addFrames(seq, scene, 3);
  const IrradianceField field = seq.reconstruct(1).field;

  RenderSettings rs;
  rs.samplesPerPass = 16;
  Renderer renderer(rs);
  FrameBuffer photons(32, 32), paths(32, 32);
  renderer.renderWithIrradiance(scene, camera, region, photons, field);
  for (int i = 0; i < 16; ++i) renderer.renderPass(scene, camera, region, paths);
  glm::dvec3 a(0.0), b(0.0), da(0.0), db(0.0);
  for (std::uint32_t y = 0; y < 32; ++y)
    for (std::uint32_t x = 0; x < 32; ++x) {
      a += glm::dvec3(photons.mean(Channel::Indirect, x, y));
      b += glm::dvec3(paths.mean(Channel::Indirect, x, y));
      da += glm::dvec3(photons.mean(Channel::Direct, x, y));
      db += glm::dvec3(paths.mean(Channel::Direct, x, y));
    }
  EXPECT_NEAR(luminance(glm::vec3(a)) / luminance(glm::vec3(b)), 1.0, 0.08);
  EXPECT_NEAR(luminance(glm::vec3(da)) / luminance(glm::vec3(db)), 1.0, 0.02);
}

TEST(EmbreePhotonSequence, RejectsBadUse) {
  PhotonSettings bad;
  bad.tMax = 0;
  EXPECT_THROW(PhotonSequence{bad}, Error);
  Scene scene(sharedDevice());
  test::cornellBox(scene, 0);
  PhotonSequence seq(smallSettings());
  EXPECT_THROW(seq.reconstruct(0), Error);
  seq.addFrame(scene, 0);
  EXPECT_THROW(seq.addFrame(scene, 2), Error);  // not consecutive
  EXPECT_THROW(seq.reconstruct(1), Error);
  Material m;
  scene.addInstance(scene.addMesh(test::quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0})), scene.addMaterial(m),
                    glm::mat4(1.0f));
  EXPECT_THROW(seq.addFrame(scene, 1), Error);  // topology changed
  Renderer renderer;
  FrameBuffer fb(4, 4);
  // The scene now has one instance more than the field's elements.
  EXPECT_THROW(renderer.renderWithIrradiance(scene, Camera{}, Region{4, 4, 0, 0, 4, 4}, fb, seq.reconstruct(0).field),
               Error);
}

TEST(EmbreePhotonSequence, FieldFitsACopyOfTheSceneWithTheSameElements) {
  // A renderer lagging the photon pass renders its own copy of the scene:
  // the field applies to it, and the image equals one rendered in the
  // scene the photons were traced in.
  Scene traced(sharedDevice()), copy(sharedDevice());
  const Camera camera = test::cornellBox(traced, 0);
  test::cornellBox(copy, 0);
  PhotonSettings s = smallSettings();
  s.photonsPerFrame = 20000;
  PhotonSequence seq(s);
  addFrames(seq, traced, 1);
  const IrradianceField field = seq.reconstruct(0).field;
  copy.commit();
  EXPECT_TRUE(field.fits(copy));
  const Region region{16, 16, 0, 0, 16, 16};
  Renderer renderer;
  FrameBuffer a(16, 16), b(16, 16);
  renderer.renderWithIrradiance(traced, camera, region, a, field);
  renderer.renderWithIrradiance(copy, camera, region, b, field);
  for (std::uint32_t y = 0; y < 16; ++y)
    for (std::uint32_t x = 0; x < 16; ++x) ASSERT_EQ(a.mean(Channel::Colour, x, y), b.mean(Channel::Colour, x, y));
}

}  // namespace
}  // namespace tsr::embree
