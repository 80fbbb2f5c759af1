// Radiance filtering (Schwenk 2013, chapter 4): properties of the filtered
// image against unfiltered path tracing with the same paths.
#include "test_scenes.hpp"

#include "tsr/embree/error.hpp"
#include "tsr/embree/radiance_filter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

namespace tsr::embree::test {
namespace {

constexpr std::uint32_t kSize = 64;

// mean((y^ - y)^2 / (y^2 + 0.01)) over pixels and colour channels.
double relMse(const std::vector<glm::vec3>& image, const std::vector<glm::vec3>& reference) {
  double sum = 0.0;
  for (std::size_t i = 0; i < image.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double d = double(image[i][c]) - double(reference[i][c]);
      sum += d * d / (double(reference[i][c]) * double(reference[i][c]) + 0.01);
    }
  return sum / double(3 * image.size());
}

std::vector<glm::vec3> colourOf(const FrameBuffer& fb) {
  std::vector<glm::vec3> out;
  for (std::uint32_t y = 0; y < fb.height(); ++y)
    for (std::uint32_t x = 0; x < fb.width(); ++x) out.push_back(fb.mean(Channel::Colour, x, y));
  return out;
}

// The Cornell box (diffuse, point light: all colour bleeding is indirect),
// optionally with a high-contrast checkerboard lying on its floor.
struct Box {
  Scene scene{sharedDevice()};
  Camera camera;
  explicit Box(bool checker = false) {
    camera = cornellBox(scene, 0);
    if (checker) {
      std::vector<glm::vec4> texels;
      for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
          texels.push_back((x / 8 + y / 8) % 2 ? glm::vec4(0.9f, 0.9f, 0.9f, 1) : glm::vec4(0.1f, 0.1f, 0.1f, 1));
      Material m;
      m.baseColor = glm::vec3(1.0f);
      m.baseColorTexture = scene.addTexture(Texture(64, 64, texels));
      scene.addInstance(scene.addMesh(quad({60, 0.5f, 20}, {500, 0.5f, 20}, {500, 0.5f, 540}, {60, 0.5f, 540})),
                        scene.addMaterial(m), glm::mat4(1.0f));
    }
  }
};

// A high-spp unfiltered reference, rendered once per scene.
const FrameBuffer& reference(Box& box, bool checker) {
  static FrameBuffer* refs[2] = {nullptr, nullptr};
  FrameBuffer*& ref = refs[checker ? 1 : 0];
  if (!ref) {
    RenderSettings s;
    s.seed = 1000;
    s.samplesPerPass = 64;
    Renderer renderer(s);
    ref = new FrameBuffer(kSize, kSize);
    render(renderer, box.scene, box.camera, Region::full(kSize, kSize), *ref, 24);  // 1536 spp
  }
  return *ref;
}

// Renders `frames` radiance passes; fb then holds the same paths unfiltered.
void radiancePasses(Renderer& renderer, Box& box, const Region& region, FrameBuffer& fb, RadianceAccumulator& acc,
                    const RadianceFilterSettings& filter, int frames) {
  for (int i = 0; i < frames; ++i) renderer.renderRadiancePass(box.scene, box.camera, region, fb, acc, filter);
}

struct Errors {
  double filtered, unfiltered;
};

Errors compareAtSpp(const RadianceFilterSettings& filter, int spp, bool checker = false) {
  Box box(checker);
  const FrameBuffer& ref = reference(box, checker);
  Renderer renderer;
  FrameBuffer fb(kSize, kSize);
  RadianceAccumulator acc(kSize, kSize);
  radiancePasses(renderer, box, Region::full(kSize, kSize), fb, acc, filter, spp);
  return {relMse(acc.radianceImage(fb), colourOf(ref)), relMse(colourOf(fb), colourOf(ref))};
}

TEST(EmbreeRadianceFilter, LowerErrorThanPathTracingAtEqualSamples) {
  for (int spp : {1, 4, 16}) {
    const Errors e = compareAtSpp({}, spp);
    std::printf("relMSE at %2d spp: filtered %.5f, unfiltered %.5f (x%.1f)\n", spp, e.filtered, e.unfiltered,
                e.unfiltered / e.filtered);
    EXPECT_LT(e.filtered, 0.5 * e.unfiltered) << spp << " spp";
  }
}

TEST(EmbreeRadianceFilter, OptionsStillBeatPathTracing) {
  RadianceFilterSettings bilateral;
  bilateral.bilateral = true;
  RadianceFilterSettings blend;
  blend.blend = 0.3f;
  RadianceFilterSettings plain;
  plain.ambientOcclusion = false;
  for (auto [name, s] : {std::pair{"defaults", RadianceFilterSettings{}}, std::pair{"bilateral", bilateral},
                         std::pair{"blend 0.3", blend}, std::pair{"no AO", plain}}) {
    const Errors e = compareAtSpp(s, 24);
    std::printf("relMSE at 24 spp, %s: filtered %.5f, unfiltered %.5f\n", name, e.filtered, e.unfiltered);
    EXPECT_LT(e.filtered, e.unfiltered) << name;
  }
}

TEST(EmbreeRadianceFilter, RadiiShrinkBelowAPixelAndTheResultConverges) {
  Box box;
  const FrameBuffer& ref = reference(box, false);
  RadianceFilterSettings filter;
  filter.threshold = 0.05f;
  Renderer renderer;
  FrameBuffer fb(kSize, kSize);
  RadianceAccumulator acc(kSize, kSize);
  const Region region = Region::full(kSize, kSize);
  auto meanRadius = [&] {
    double sum = 0.0;
    for (std::uint32_t y = 0; y < kSize; ++y)
      for (std::uint32_t x = 0; x < kSize; ++x) sum += acc.radius(x, y);
    return sum / double(kSize * kSize);
  };
  auto filteredShare = [&] {
    int n = 0;
    for (std::uint32_t y = 0; y < kSize; ++y)
      for (std::uint32_t x = 0; x < kSize; ++x) n += acc.radius(x, y) >= 1.0f;
    return double(n) / double(kSize * kSize);
  };
  radiancePasses(renderer, box, region, fb, acc, filter, 1);
  const double r1 = meanRadius();
  radiancePasses(renderer, box, region, fb, acc, filter, 7);
  const double r8 = meanRadius();
  radiancePasses(renderer, box, region, fb, acc, filter, 24);
  const double r32 = meanRadius();
  std::printf("mean radius: frame 1 %.2f, frame 8 %.2f, frame 32 %.2f\n", r1, r8, r32);
  EXPECT_GT(r1, r8);
  EXPECT_GT(r8, r32);
  radiancePasses(renderer, box, region, fb, acc, filter, 480);  // 512 spp
  const double share = filteredShare();
  const double eFiltered = relMse(acc.radianceImage(fb), colourOf(ref));
  const double eUnfiltered = relMse(colourOf(fb), colourOf(ref));
  const double apart = relMse(acc.radianceImage(fb), colourOf(fb));
  std::printf("512 spp: filtered share %.4f, relMSE filtered %.6f, unfiltered %.6f, filtered vs unfiltered %.6f\n",
              share, eFiltered, eUnfiltered, apart);
  EXPECT_LT(share, 0.01) << "nearly every pixel accumulates unfiltered samples";
  EXPECT_LT(eFiltered, 2.0 * eUnfiltered + 1e-4);
  EXPECT_LT(apart, 2e-3);
}

TEST(EmbreeRadianceFilter, TextureEdgesStaySharp) {
  // The checkerboard's squares differ by 9x in albedo. Radiance filtering
  // evaluates each pixel's own BSDF, so the indirect light of pixels next to
  // an edge keeps the ratio; filtering pixel values would blur it away.
  Box box(true);
  const FrameBuffer& ref = reference(box, true);
  Renderer renderer;
  FrameBuffer fb(kSize, kSize);
  RadianceAccumulator acc(kSize, kSize);
  radiancePasses(renderer, box, Region::full(kSize, kSize), fb, acc, {}, 4);
  double bright = 0.0, dark = 0.0, refBright = 0.0, refDark = 0.0;
  int nb = 0, nd = 0;
  for (std::uint32_t y = 1; y + 1 < kSize; ++y)
    for (std::uint32_t x = 1; x + 1 < kSize; ++x) {
      // The checkerboard's grey squares, not the white, red and green walls.
      const glm::vec3 al = ref.albedo(x, y);
      if (std::abs(al.x - al.y) > 0.02f || std::abs(al.y - al.z) > 0.02f) continue;
      const float a = al.x;
      const bool isBright = a > 0.85f && a<0.95f, isDark = a> 0.05f && a < 0.15f;
      if (!isBright && !isDark) continue;
      bool nearEdge = false;  // a 4-neighbour of the other kind
      for (auto [dx, dy] : {std::pair{-1, 0}, std::pair{1, 0}, std::pair{0, -1}, std::pair{0, 1}}) {
        const float b = ref.albedo(x + dx, y + dy).x;
        nearEdge = nearEdge || (isBright ? b < 0.5f : b > 0.5f && b < 0.95f);
      }
      if (!nearEdge) continue;
      const double v = luminance(acc.indirect(x, y)), r = luminance(ref.mean(Channel::Indirect, x, y));
      (isBright ? bright : dark) += v;
      (isBright ? refBright : refDark) += r;
      ++(isBright ? nb : nd);
    }
  ASSERT_GT(nb, 20);
  ASSERT_GT(nd, 20);
  const double ratio = (bright / nb) / (dark / nd), refRatio = (refBright / nb) / (refDark / nd);
  std::printf("edge pixels: indirect bright/dark %.2f (reference %.2f)\n", ratio, refRatio);
  EXPECT_GT(ratio, 0.75 * refRatio);
  const Errors e = compareAtSpp({}, 4, true);
  std::printf("checkerboard relMSE at 4 spp: filtered %.5f, unfiltered %.5f\n", e.filtered, e.unfiltered);
  EXPECT_LT(e.filtered, e.unfiltered);
}

TEST(EmbreeRadianceFilter, ThreadCountAndTilingDoNotChangeTheImage) {
  Box box;
  RenderSettings a;
  a.threads = 1;
  a.tileSize = 7;
  RenderSettings b = a;
  b.threads = 2;
  b.tileSize = 16;
  Renderer ra(a), rb(b);
  FrameBuffer fa(kSize, kSize), fb(kSize, kSize);
  RadianceAccumulator aa(kSize, kSize), ab(kSize, kSize);
  RadianceFilterSettings filter;
  filter.bilateral = true;
  filter.blend = 0.2f;
  const Region region = Region::full(kSize, kSize);
  radiancePasses(ra, box, region, fa, aa, filter, 20);
  radiancePasses(rb, box, region, fb, ab, filter, 20);
  EXPECT_TRUE(identical(fa, fb));
  EXPECT_EQ(aa.radianceImage(fa), ab.radianceImage(fb));
}

TEST(EmbreeRadianceFilter, RestartsWithTheFrameBuffer) {
  Box box;
  Renderer renderer;
  FrameBuffer fb(kSize, kSize);
  RadianceAccumulator acc(kSize, kSize);
  const Region region = Region::full(kSize, kSize);
  radiancePasses(renderer, box, region, fb, acc, {}, 3);
  EXPECT_EQ(acc.frames(5, 5), 3u);
  Camera moved = box.camera;
  moved.cameraToWorld[3].x += 10.0f;
  auto result = renderer.renderRadiancePass(box.scene, moved, region, fb, acc, {});
  EXPECT_TRUE(result.restarted);
  EXPECT_EQ(acc.frames(5, 5), 1u);
  EXPECT_EQ(fb.sampleCount(5, 5), 1u);
  fb.reset();  // a restart by anyone else is noticed too
  renderer.renderRadiancePass(box.scene, moved, region, fb, acc, {});
  EXPECT_EQ(acc.frames(5, 5), 1u);
}

TEST(EmbreeRadianceFilter, PathAndRadianceSamplesDoNotMix) {
  Box box;
  Renderer renderer;
  FrameBuffer fb(kSize, kSize);
  RadianceAccumulator acc(kSize, kSize);
  const Region region = Region::full(kSize, kSize);
  renderer.renderPass(box.scene, box.camera, region, fb);
  renderer.renderPass(box.scene, box.camera, region, fb);
  EXPECT_FALSE(renderer.restartIfStale(box.scene, box.camera, region, fb, Estimator::Paths));
  EXPECT_EQ(fb.sampleCount(5, 5), 2u);
  EXPECT_TRUE(renderer.restartIfStale(box.scene, box.camera, region, fb, Estimator::Radiance));
  EXPECT_EQ(fb.sampleCount(5, 5), 0u);
  EXPECT_FALSE(renderer.renderRadiancePass(box.scene, box.camera, region, fb, acc, {}).restarted);
  EXPECT_FALSE(renderer.renderFlashPass(box.scene, box.camera, region, fb, 2).restarted)
      << "flash samples join the radiance samples held";
  EXPECT_FALSE(renderer.restartIfStale(box.scene, box.camera, region, fb, Estimator::Radiance));
  EXPECT_EQ(fb.sampleCount(5, 5), 1u);
  EXPECT_TRUE(renderer.renderPass(box.scene, box.camera, region, fb).restarted);
}

TEST(EmbreeRadianceFilter, RejectsBadSettingsAndSizes) {
  Box box;
  Renderer renderer;
  FrameBuffer fb(kSize, kSize);
  RadianceAccumulator acc(kSize, kSize), small(8, 8);
  const Region region = Region::full(kSize, kSize);
  RadianceFilterSettings s;
  s.threshold = 0.0f;
  EXPECT_THROW(renderer.renderRadiancePass(box.scene, box.camera, region, fb, acc, s), Error);
  s = {};
  s.warmupFrames = 0;
  EXPECT_THROW(renderer.renderRadiancePass(box.scene, box.camera, region, fb, acc, s), Error);
  s = {};
  s.blend = 1.0f;
  EXPECT_THROW(renderer.renderRadiancePass(box.scene, box.camera, region, fb, acc, s), Error);
  s = {};
  s.maxRadius = NAN;
  EXPECT_THROW(renderer.renderRadiancePass(box.scene, box.camera, region, fb, acc, s), Error);
  EXPECT_THROW(renderer.renderRadiancePass(box.scene, box.camera, region, fb, small, {}), Error);
  EXPECT_EQ(fb.sampleCount(0, 0), 0u) << "nothing rendered";
}

TEST(EmbreeRadianceFilter, HybridMaskMarksPixelsSeenThroughMirrorAndGlass) {
  // Floor under a lamp; a glass sphere on it and a mirror standing at the
  // back, facing the camera at a slant.
  Scene scene(sharedDevice());
  floorUnderLamp(scene);
  Material glass;
  glass.type = MaterialType::Glass;
  glass.baseColor = glm::vec3(1.0f);
  scene.addInstance(scene.addMesh(uvSphere({0, 1, 0}, 1.0f, 800, true)), scene.addMaterial(glass), glm::mat4(1.0f));
  Material mirror;
  mirror.type = MaterialType::Mirror;
  mirror.baseColor = glm::vec3(0.9f);
  scene.addInstance(scene.addMesh(quad({2, 0, -3}, {5, 0, -1}, {5, 3, -1}, {2, 3, -3})), scene.addMaterial(mirror),
                    glm::mat4(1.0f));
  const Camera camera = Camera::lookAt({0, 3, 7}, {0, 1, 0}, {0, 1, 0}, glm::radians(50.0f), 1.0f);
  Renderer renderer;
  FrameBuffer fb(kSize, kSize);
  RadianceAccumulator acc(kSize, kSize);
  const Region region = Region::full(kSize, kSize);
  for (int i = 0; i < 8; ++i) renderer.renderRadiancePass(scene, camera, region, fb, acc, {});
  int glassPixels = 0, mirrorPixels = 0;
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      const std::uint8_t m = acc.mask(x, y);
      if (m & kMaskReflectRefract) {
        ++glassPixels;
        EXPECT_TRUE(m & kMaskSpecular);
        // Left to pixel filtering: the running mean of the unfiltered paths.
        EXPECT_EQ(acc.indirect(x, y), fb.mean(Channel::Indirect, x, y) - fb.mean(Channel::Caustic, x, y));
        EXPECT_EQ(acc.radius(x, y), 0.0f);
      } else if (m & kMaskSpecular) {
        ++mirrorPixels;
      }
    }
  // The sphere's centre, through the glass; the floor in front of it, plain.
  EXPECT_TRUE(acc.mask(kSize / 2, kSize / 2) & kMaskReflectRefract);
  EXPECT_EQ(acc.mask(kSize / 2, kSize - 3), 0);
  EXPECT_GT(glassPixels, 50);
  EXPECT_GT(mirrorPixels, 20) << "the mirror reflects the floor: specular, not reflect-refract";
}

TEST(EmbreeRadianceFilter, CropWithHaloMatchesTheFullImage) {
  // A crop with a halo of maxRadius sees, for its inner pixels, the same
  // samples in every kernel. During warm-up the radii do not depend on the
  // variance, so the inner pixels are identical. Afterwards the radius reads
  // the filtered perceived variance, whose background radiance is the
  // neighbours' filtered result of the previous frame: it reaches one
  // maxRadius further each frame, past the halo. Inner pixels then differ by
  // the effect of slightly different radii only.
  Box box;
  RadianceFilterSettings filter;
  filter.maxRadius = 6.0f;
  const std::uint32_t halo = 6;
  Renderer renderer;
  FrameBuffer full(kSize, kSize);
  RadianceAccumulator fullAcc(kSize, kSize);
  const Region crop{kSize, kSize, 20 - halo, 24 - halo, 44 + halo, 40 + halo};
  FrameBuffer part(crop.regionWidth(), crop.regionHeight());
  RadianceAccumulator partAcc(crop.regionWidth(), crop.regionHeight());
  auto compare = [&](double& meanRel, double& maxRel) {
    meanRel = maxRel = 0.0;
    int n = 0;
    for (std::uint32_t y = 24; y < 40; ++y)
      for (std::uint32_t x = 20; x < 44; ++x) {
        const float a = luminance(fullAcc.radiance(full, x, y));
        const float b = luminance(partAcc.radiance(part, x - crop.x0, y - crop.y0));
        const double rel = std::abs(a - b) / (std::abs(a) + 0.01);
        meanRel += rel;
        maxRel = std::max(maxRel, rel);
        ++n;
      }
    meanRel /= n;
  };
  for (std::uint32_t i = 0; i < filter.warmupFrames; ++i) {
    renderer.renderRadiancePass(box.scene, box.camera, Region::full(kSize, kSize), full, fullAcc, filter);
    renderer.renderRadiancePass(box.scene, box.camera, crop, part, partAcc, filter);
  }
  double meanRel, maxRel;
  compare(meanRel, maxRel);
  EXPECT_EQ(maxRel, 0.0) << "identical through the warm-up frames";
  for (int i = 0; i < 12; ++i) {
    renderer.renderRadiancePass(box.scene, box.camera, Region::full(kSize, kSize), full, fullAcc, filter);
    renderer.renderRadiancePass(box.scene, box.camera, crop, part, partAcc, filter);
  }
  compare(meanRel, maxRel);
  std::printf("crop vs full after 16 frames: mean relative difference %.5f, max %.5f\n", meanRel, maxRel);
  EXPECT_LT(meanRel, 0.01);
  EXPECT_LT(maxRel, 0.1);
}

}  // namespace
}  // namespace tsr::embree::test
