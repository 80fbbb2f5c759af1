// Alpha-tested surfaces (AlphaMode) and texture transforms: a quad whose
// alpha cuts half of it away casts a shadow of the other half only; a
// blended quad of opacity a passes 1 - a of the light on average; blended
// renders are bitwise alike on one thread and two; an opaque mode ignores
// alpha; a texture transform moves the texture.
#include <gtest/gtest.h>

#include "test_scenes.hpp"

namespace tsr::embree::test {
namespace {

// A grey floor lit straight from above, a 2x2 quad at height 1 over it
// (its left half at lowest x), and a camera below the quad's height that
// sees the floor under the quad but not the quad.
struct ShadowScene {
  Scene scene{sharedDevice()};
  Camera camera = Camera::lookAt({0, 0.9f, 2.5f}, {0, 0, 0}, {0, 1, 0}, glm::radians(16.0f), 1.0f);

  // `halfCut`: the cover's alpha texture is opaque on its left half and
  // clear on its right.
  ShadowScene(Material cover, bool halfCut = false) {
    Material grey;
    grey.baseColor = glm::vec3(0.5f);
    scene.addInstance(scene.addMesh(quad({-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, {-5, 0, -5})), scene.addMaterial(grey),
                      glm::mat4(1.0f));
    if (halfCut)
      cover.baseColorTexture = scene.addTexture(Texture(2, 1, {glm::vec4(1.0f), glm::vec4(1.0f, 1.0f, 1.0f, 0.0f)}));
    scene.addInstance(scene.addMesh(quad({-1, 1, 1}, {1, 1, 1}, {1, 1, -1}, {-1, 1, -1})), scene.addMaterial(cover),
                      glm::mat4(1.0f));
    scene.addLight(DirectionalLight{{0, -1, 0}, glm::vec3(3.0f)});
  }
};

// Mean green of the middle rows' left and right thirds: the floor under
// the quad's two halves.
std::pair<float, float> underHalves(const FrameBuffer& fb) {
  double left = 0, right = 0;
  const std::uint32_t w = fb.width(), h = fb.height();
  for (std::uint32_t y = h / 3; y < 2 * h / 3; ++y)
    for (std::uint32_t x = 0; x < w / 3; ++x) {
      left += fb.colour(x, y).g;
      right += fb.colour(w - 1 - x, y).g;
    }
  return {float(left), float(right)};
}

FrameBuffer renderOf(ShadowScene& s, int threads = 0) {
  RenderSettings settings;
  settings.samplesPerPass = 8;
  settings.threads = threads;
  settings.maxDepth = 1;  // direct light only: the shadow is all there is
  Renderer renderer(settings);
  FrameBuffer fb(24, 24);
  render(renderer, s.scene, s.camera, Region::full(24, 24), fb, 4);
  return fb;
}

Material withMode(AlphaMode mode) {
  Material m;
  m.alphaMode = mode;
  return m;
}

TEST(EmbreeAlpha, AMaskedQuadCastsAMaskedShadow) {
  ShadowScene cut(withMode(AlphaMode::Mask), true);
  auto [left, right] = underHalves(renderOf(cut));
  EXPECT_GT(right, 0.0f);
  EXPECT_LT(left, 0.05f * right) << "the opaque half shadows, the cut half lets the light through";
  ShadowScene solid(withMode(AlphaMode::Opaque), true);
  const float solidRight = std::get<1>(underHalves(renderOf(solid)));
  EXPECT_LT(solidRight, 0.05f * right) << "Opaque ignores alpha";
}

TEST(EmbreeAlpha, ABlendedQuadPassesOneMinusItsOpacity) {
  Material none;
  none.opacity = 0.0f;
  none.alphaMode = AlphaMode::Blend;
  ShadowScene clear(none);
  const float lit = std::get<0>(underHalves(renderOf(clear)));
  Material quarter;
  quarter.opacity = 0.25f;
  quarter.alphaMode = AlphaMode::Blend;
  ShadowScene blended(quarter);
  auto [left, right] = underHalves(renderOf(blended));
  EXPECT_NEAR(left / lit, 0.75f, 0.03f);
  EXPECT_NEAR(right / lit, 0.75f, 0.03f);
}

TEST(EmbreeAlpha, BlendedRendersAreBitwiseAlikeOnOneThreadAndTwo) {
  Material m;
  m.opacity = 0.5f;
  m.alphaMode = AlphaMode::Blend;
  ShadowScene a(m), b(m);
  EXPECT_TRUE(identical(renderOf(a, 1), renderOf(b, 2)));
}

TEST(EmbreeAlpha, ATextureTransformMovesTheTexture) {
  // A red | green texture on a quad facing the camera, then moved by half.
  auto halves = [](const UvTransform& t) {
    Scene scene(sharedDevice());
    Material m;
    m.baseColor = glm::vec3(1.0f);
    m.baseColorTexture = scene.addTexture(Texture(2, 1, {glm::vec4(1, 0, 0, 1), glm::vec4(0, 1, 0, 1)}));
    m.baseColorUv = t;
    scene.addInstance(scene.addMesh(quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0})), scene.addMaterial(m),
                      glm::mat4(1.0f));
    scene.setEnvironment(Environment::constant(glm::vec3(1.0f)));
    Camera camera = Camera::lookAt({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, glm::radians(30.0f), 1.0f);
    RenderSettings settings;
    settings.samplesPerPass = 4;
    Renderer renderer(settings);
    FrameBuffer fb(16, 16);
    render(renderer, scene, camera, Region::full(16, 16), fb, 1);
    const glm::vec4 left = fb.colour(5, 8), right = fb.colour(10, 8);
    return std::pair{left.r > left.g, right.r > right.g};
  };
  EXPECT_EQ(halves({}), std::pair(true, false)) << "red left, green right";
  EXPECT_EQ(halves({{1, 0, 0.5f}, {0, 1, 0}}), std::pair(false, true)) << "moved by half: green left";
}

}  // namespace
}  // namespace tsr::embree::test
