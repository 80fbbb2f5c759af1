#include "test_util.hpp"

#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

namespace tsr::vk {
namespace {

using test::device;

const Camera kCam = Camera::lookAt({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 1.2f, 1.0f);
const Region kFull = Region::full(64, 64);

Material emissive(glm::vec3 e, float opacity = 1.0f) {
  Material m;
  m.baseColor = glm::vec3(0.0f);
  m.emission = e;
  m.opacity = opacity;
  return m;
}

TEST(VulkanMaterial, HalfTransparentRedOverBlueBlends) {
  for (bool redFirst : {true, false}) {
    Scene scene(device());
    MeshId quad = scene.addMesh(test::quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}));
    MaterialId red = scene.addMaterial(emissive({1, 0, 0}, 0.5f));
    MaterialId blue = scene.addMaterial(emissive({0, 0, 1}));
    const glm::mat4 front = glm::translate(glm::mat4(1.0f), {0.5f, 0, 0.5f});
    if (redFirst) scene.addInstance(quad, red, front);
    scene.addInstance(quad, blue, glm::mat4(1.0f));
    if (!redFirst) scene.addInstance(quad, red, front);
    Renderer renderer(device(), {.background = {0, 0, 0, 0}});
    FrameBuffer fb(64, 64);
    renderer.render(scene, kCam, kFull, fb);
    test::writePng("/tmp/tsr_vk_transparency.png", fb);

    glm::vec2 both = test::project(kCam, kFull, {0.7f, 0.2f, 0.5f});
    glm::vec4 c = fb.colour(int(both.x), int(both.y));
    EXPECT_NEAR(c.r, 0.5f, 1e-5f);
    EXPECT_NEAR(c.g, 0.0f, 1e-5f);
    EXPECT_NEAR(c.b, 0.5f, 1e-5f);
    EXPECT_NEAR(c.a, 1.0f, 1e-5f);
    // No depth write: depth is the blue quad's (distance 3), not the red one's (2.5).
    EXPECT_NEAR(fb.depth(int(both.x), int(both.y)), 3.0f, 1e-3f);

    glm::vec2 redOnly = test::project(kCam, kFull, {1.3f, 0.2f, 0.5f});
    c = fb.colour(int(redOnly.x), int(redOnly.y));
    EXPECT_NEAR(c.r, 0.5f, 1e-5f);
    EXPECT_NEAR(c.a, 0.5f, 1e-5f);  // coverage over the transparent background
    EXPECT_TRUE(std::isinf(fb.depth(int(redOnly.x), int(redOnly.y))));
  }
}

// Two transparent layers must be composited back to front whatever their order in the scene.
TEST(VulkanMaterial, TransparentLayersSortedBackToFront) {
  Scene scene(device());
  MeshId quad = scene.addMesh(test::quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}));
  MaterialId near = scene.addMaterial(emissive({1, 0, 0}, 0.5f));
  MaterialId far = scene.addMaterial(emissive({0, 1, 0}, 0.5f));
  scene.addInstance(quad, near, glm::translate(glm::mat4(1.0f), {0, 0, 1.0f}));
  scene.addInstance(quad, far, glm::mat4(1.0f));
  Renderer renderer(device());
  FrameBuffer fb(64, 64);
  renderer.render(scene, kCam, kFull, fb);
  glm::vec4 c = fb.colour(32, 32);
  // far over background: (0, .5, 0, .5); near over that: (.5, .25, 0, .75)
  EXPECT_NEAR(c.r, 0.5f, 1e-5f);
  EXPECT_NEAR(c.g, 0.25f, 1e-5f);
  EXPECT_NEAR(c.a, 0.75f, 1e-5f);
}

// A 4x4 sRGB texture with one colour per 2x2 quadrant; uv (0, 0) is the
// top-left texel, mapped to the quad's top-left corner. Two of the points
// looked at lie on the quad's diagonal, where lavapipe's derivatives gave a
// level of detail of 1.6 instead of -3 (the quadrants blurred together).
TEST(VulkanMaterial, BaseColourTextureLookupAtKnownUv) {
  const std::uint8_t q[4][4] = {{255, 0, 0, 255}, {0, 255, 0, 255}, {0, 0, 255, 255}, {128, 128, 128, 255}};
  std::vector<std::uint8_t> texels;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const std::uint8_t* c = q[(y / 2) * 2 + x / 2];
      texels.insert(texels.end(), c, c + 4);
    }
  Scene scene(device());
  TextureId tex = scene.addTexture(Texture::fromRgba8(4, 4, texels));
  Material m;
  m.baseColor = glm::vec3(1.0f);
  m.baseColorTexture = tex;
  scene.addInstance(scene.addMesh(test::quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0})), scene.addMaterial(m),
                    glm::mat4(1.0f));
  scene.setEnvironment(Environment::constant(glm::vec3(1.0f)));  // radiance = albedo
  Renderer renderer(device());
  FrameBuffer fb(64, 64);
  renderer.render(scene, kCam, kFull, fb);
  test::writePng("/tmp/tsr_vk_texture.png", fb);

  auto at = [&](float u, float v) {
    glm::vec2 px = test::project(kCam, kFull, {-1.0f + 2.0f * u, 1.0f - 2.0f * v, 0.0f});
    return fb.colour(int(px.x), int(px.y));
  };
  const float grey = std::pow((128.0f / 255.0f + 0.055f) / 1.055f, 2.4f);  // sRGB decode
  const glm::vec3 expected[4] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, glm::vec3(grey)};
  const glm::vec2 uvs[4] = {{0.25f, 0.25f}, {0.75f, 0.25f}, {0.25f, 0.75f}, {0.75f, 0.75f}};
  for (int i = 0; i < 4; ++i) {
    glm::vec4 c = at(uvs[i].x, uvs[i].y);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], expected[i][k], 0.01f) << "quadrant " << i << " channel " << k;
  }
  EXPECT_THROW(scene.removeTexture(tex), Error);  // still used by the material
}

// A 256x256 checkerboard of single black and white texels on a quad about
// 30 pixels wide: without mip levels each pixel picks up one or two texels
// (black, white or anything between: moire); with them every pixel is the
// checkerboard's mean, 0.5 in linear light (averaging the sRGB-encoded
// bytes instead would give 0.21).
TEST(VulkanMaterial, AMinifiedTextureAveragesInsteadOfAliasing) {
  constexpr int kSide = 256;
  std::vector<std::uint8_t> texels;
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      const std::uint8_t v = (x + y) % 2 ? 255 : 0;
      texels.insert(texels.end(), {v, v, v, 255});
    }
  Scene scene(device());
  Material m = emissive({1, 1, 1});
  m.emissionTexture = scene.addTexture(Texture::fromRgba8(kSide, kSide, texels));
  scene.addInstance(scene.addMesh(test::quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0})), scene.addMaterial(m),
                    glm::mat4(1.0f));
  Renderer renderer(device(), {.background = {0, 0, 0, 0}});
  FrameBuffer fb(64, 64);
  renderer.render(scene, kCam, kFull, fb);
  test::writePng("/tmp/tsr_vk_minified.png", fb);
  const glm::vec2 lo = test::project(kCam, kFull, {-0.8f, 0.8f, 0.0f});
  const glm::vec2 hi = test::project(kCam, kFull, {0.8f, -0.8f, 0.0f});
  int pixels = 0;
  for (int y = int(lo.y); y <= int(hi.y); ++y)
    for (int x = int(lo.x); x <= int(hi.x); ++x, ++pixels)
      ASSERT_NEAR(fb.colour(x, y).r, 0.5f, 0.03f) << "pixel " << x << "," << y;
  EXPECT_GT(pixels, 400);
}

// glTF's MASK: a red quad whose texture is opaque on its left half and
// clear on its right, in front of a blue one, cut at 0.5: blue shows
// through the clear half only, and the red half is opaque (depth written).
// 4x4 white texels, opaque on the left half (u < 0.5), clear on the right.
std::vector<std::uint8_t> halfCut() {
  std::vector<std::uint8_t> texels;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) texels.insert(texels.end(), {255, 255, 255, std::uint8_t(x < 2 ? 255 : 0)});
  return texels;
}

TEST(VulkanMaterial, MaskedAlphaCutsTheClearHalfAway) {
  for (float cutoff : {0.5f, 0.0f}) {
    const std::vector<std::uint8_t> texels = halfCut();
    Scene scene(device());
    MeshId quad = scene.addMesh(test::quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}));
    Material red = emissive({1, 0, 0});
    red.baseColorTexture = scene.addTexture(Texture::fromRgba8(4, 4, texels));
    red.alphaCutoff = cutoff;
    scene.addInstance(quad, scene.addMaterial(red), glm::translate(glm::mat4(1.0f), {0, 0, 0.5f}));
    scene.addInstance(quad, scene.addMaterial(emissive({0, 0, 1})), glm::scale(glm::mat4(1.0f), glm::vec3(2.0f)));
    Renderer renderer(device(), {.background = {0, 0, 0, 0}});
    FrameBuffer fb(64, 64);
    renderer.render(scene, kCam, kFull, fb);
    const glm::vec2 left = test::project(kCam, kFull, {-0.5f, 0.0f, 0.5f});
    const glm::vec2 right = test::project(kCam, kFull, {0.5f, 0.0f, 0.5f});
    EXPECT_NEAR(fb.colour(int(left.x), int(left.y)).r, 1.0f, 1e-5f) << "cut-off " << cutoff;
    EXPECT_NEAR(fb.depth(int(left.x), int(left.y)), 2.5f, 1e-3f) << "opaque where kept";
    const glm::vec4 seen = fb.colour(int(right.x), int(right.y));
    if (cutoff > 0.0f) {
      EXPECT_NEAR(seen.b, 1.0f, 1e-5f) << "the blue quad through the cut half";
      EXPECT_NEAR(fb.depth(int(right.x), int(right.y)), 3.0f, 1e-3f);
    } else {
      EXPECT_NEAR(seen.r, 1.0f, 1e-5f) << "no cut-off: opaque everywhere";
    }
  }
}

// MASK over a minified texture: one texel in four opaque (alpha 255), cut
// at 0.5. Alpha averaged down the mip chain is 0.25 everywhere, which would
// cut the whole quad away (foliage thinning out with distance); the cut
// reads the first level, so about a quarter of the quad stays.
TEST(VulkanMaterial, MaskedCutOffReadsTheFirstLevelWhenMinified) {
  constexpr int kSide = 256;
  std::vector<std::uint8_t> texels;
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x)
      texels.insert(texels.end(), {255, 255, 255, std::uint8_t(x % 2 || y % 2 ? 0 : 255)});
  Scene scene(device());
  Material red = emissive({1, 0, 0});
  red.baseColorTexture = scene.addTexture(Texture::fromRgba8(kSide, kSide, texels));
  red.alphaCutoff = 0.5f;
  scene.addInstance(scene.addMesh(test::quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0})), scene.addMaterial(red),
                    glm::mat4(1.0f));
  Renderer renderer(device(), {.background = {0, 0, 0, 0}});
  FrameBuffer fb(64, 64);
  renderer.render(scene, kCam, kFull, fb);
  const glm::vec2 lo = test::project(kCam, kFull, {-0.8f, 0.8f, 0.0f});
  const glm::vec2 hi = test::project(kCam, kFull, {0.8f, -0.8f, 0.0f});
  int kept = 0, pixels = 0;
  for (int y = int(lo.y); y <= int(hi.y); ++y)
    for (int x = int(lo.x); x <= int(hi.x); ++x, ++pixels) kept += fb.colour(x, y).r > 0.5f;
  EXPECT_GT(kept, pixels / 10) << kept << " of " << pixels << " pixels kept";
  EXPECT_LT(kept, pixels * 6 / 10) << kept << " of " << pixels << " pixels kept";
}

// A masked quad between a directional light and a white floor: the floor
// is in shadow under the kept half and lit under the cut half (the shadow
// pass cuts the quad as the main pass does); without a cut-off the whole
// quad casts a shadow.
TEST(VulkanMaterial, MaskedQuadCastsAMaskedShadow) {
  for (float cutoff : {0.5f, 0.0f}) {
    const std::vector<std::uint8_t> texels = halfCut();
    Scene scene(device());
    Material white;
    white.baseColor = glm::vec3(0.8f);
    scene.addInstance(scene.addMesh(test::quad({-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, {-2, 0, -2})),
                      scene.addMaterial(white), glm::mat4(1.0f));
    Material cut = white;
    cut.baseColorTexture = scene.addTexture(Texture::fromRgba8(4, 4, texels));
    cut.alphaCutoff = cutoff;
    // Two units above the floor; the camera sees the floor under it past
    // its near edge.
    scene.addInstance(scene.addMesh(test::quad({-1, 1, 0.5f}, {1, 1, 0.5f}, {1, 1, -0.5f}, {-1, 1, -0.5f})),
                      scene.addMaterial(cut), glm::translate(glm::mat4(1.0f), {0, 1, 0}));
    scene.addLight(
        DirectionalLight{.direction = glm::normalize(glm::vec3(0.3f, -1, 0.0f)), .irradiance = glm::vec3(2.0f)});
    Renderer renderer(device());
    FrameBuffer fb(64, 64);
    // The floor under each half's centre along the light: x = -0.5 and
    // +0.5 at height 2, shifted by 0.6 along +x on the way down.
    const Camera cam = Camera::lookAt({0, 4, 3}, {0, 0, 0}, {0, 1, 0}, 1.2f, 1.0f);
    renderer.render(scene, cam, kFull, fb);
    test::writePng("/tmp/tsr_vk_masked_shadow_" + std::to_string(int(cutoff * 10)) + ".png", fb);
    const glm::vec2 kept = test::project(cam, kFull, {-0.5f + 0.6f, 0, 0});
    const glm::vec2 gone = test::project(cam, kFull, {0.5f + 0.6f, 0, 0});
    const glm::vec2 open = test::project(cam, kFull, {0.0f, 0, 1.6f});
    const float lit = fb.colour(int(open.x), int(open.y)).r;
    EXPECT_GT(lit, 0.1f) << "the floor is lit away from the quad";
    EXPECT_LT(fb.colour(int(kept.x), int(kept.y)).r, 0.2f * lit) << "cut-off " << cutoff << ": shadow of the kept half";
    if (cutoff > 0.0f)
      EXPECT_NEAR(fb.colour(int(gone.x), int(gone.y)).r, lit, 0.05f * lit) << "the light passes the cut half";
    else
      EXPECT_LT(fb.colour(int(gone.x), int(gone.y)).r, 0.2f * lit) << "no cut-off: the whole quad casts a shadow";
  }
}

TEST(VulkanMaterial, MsaaResolvesInteriorExactlyAndBlendsEdges) {
  Scene scene(device());
  // A quad whose left edge runs diagonally through pixels.
  scene.addInstance(scene.addMesh(test::quad({-0.7f, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-0.3f, 1, 0})),
                    scene.addMaterial(emissive({1, 1, 1})), glm::mat4(1.0f));
  FrameBuffer one(64, 64), four(64, 64);
  Renderer renderer(device(), {.msaaSamples = 1});
  renderer.render(scene, kCam, kFull, one);
  renderer.setSettings({.msaaSamples = 4});
  renderer.render(scene, kCam, kFull, four);
  EXPECT_EQ(four.colour(40, 32), glm::vec4(1.0f));
  EXPECT_EQ(one.colour(40, 32), glm::vec4(1.0f));
  int partial = 0;
  for (std::uint32_t y = 0; y < 64; ++y)
    for (std::uint32_t x = 0; x < 64; ++x) {
      float a = four.colour(x, y).a;
      if (a > 0.1f && a < 0.9f) ++partial;
      EXPECT_TRUE(one.colour(x, y).a == 0.0f || one.colour(x, y).a == 1.0f);
    }
  EXPECT_GT(partial, 10);
  // Depth of the resolved image is sample 0's: finite inside, infinite outside.
  EXPECT_NEAR(four.depth(40, 32), 3.0f, 1e-3f);
  EXPECT_TRUE(std::isinf(four.depth(2, 32)));
}

TEST(VulkanMaterial, ConductorHighlightPeaksAtMirrorDirection) {
  Scene scene(device());
  Material metal;
  metal.type = MaterialType::Conductor;
  metal.baseColor = glm::vec3(0.9f);
  metal.roughness = 0.3f;
  scene.addInstance(scene.addMesh(test::quad({-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0})), scene.addMaterial(metal),
                    glm::mat4(1.0f));
  scene.addLight(PointLight{{0, 0, 3}, glm::vec3(10.0f)});  // at the eye: mirror point is the centre
  Renderer renderer(device());
  FrameBuffer fb(64, 64);
  renderer.render(scene, kCam, kFull, fb);
  const float centre = fb.colour(32, 32).r;
  EXPECT_GT(centre, fb.colour(50, 32).r * 2.0f);
  EXPECT_GT(centre, fb.colour(32, 10).r * 2.0f);
  // Analytic GGX with the light at the eye: h = wo = wi, Schlick F = F0.
  const float a = 0.09f;
  for (int px : {31, 33, 36}) {
    glm::vec3 p = test::pixelOnPlane(kCam, kFull, px, 31, {0, 0, 1}, 0.0f);
    glm::vec3 d = glm::vec3(0, 0, 3) - p;
    float r2 = glm::dot(d, d);
    float c = d.z / std::sqrt(r2);
    float t = c * c * (a * a - 1.0f) + 1.0f;
    float D = a * a / (3.14159265f * t * t);
    float lambda = 0.5f * (-1.0f + std::sqrt(1.0f + a * a * (1.0f - c * c) / (c * c)));
    float G2 = 1.0f / (1.0f + 2.0f * lambda);
    float expected = 0.9f * D * G2 / (4.0f * c) * c * 10.0f / r2;
    EXPECT_NEAR(fb.colour(px, 31).r, expected, 0.02f * expected) << px;
  }
}

}  // namespace
}  // namespace tsr::vk
