// glTF's metallic-roughness BRDF in the rasterizer (issue 28): properties,
// not pixels copied from a run.
#include "reflections/brdf_table.hpp"
#include "test_util.hpp"

#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace tsr::vk {
namespace {

using test::device;

constexpr float kPi = std::numbers::pi_v<float>;

Material gltf(glm::vec3 base, float metallic, float roughness) {
  Material m;
  m.type = MaterialType::MetallicRoughness;
  m.baseColor = base;
  m.metallic = metallic;
  m.roughness = roughness;
  return m;
}

// The split-sum table against an independent integration: a midpoint rule
// over the hemisphere of f cos split by Schlick's factor, with the same D
// and G2 (alpha = roughness^2). 1 % where the lobe is wide enough for the grid.
TEST(VulkanGltfMaterial, SplitSumTableMatchesQuadrature) {
  constexpr std::uint32_t kSize = 8;
  const std::vector<glm::vec2> table = splitSumTable(kSize, 4096);
  auto lambda = [](float c, float a) {
    const float t2 = std::max(0.0f, 1.0f - c * c) / (c * c);
    return 0.5f * (-1.0f + std::sqrt(1.0f + a * a * t2));
  };
  int checked = 0;
  for (std::uint32_t j = 3; j < kSize; ++j)
    for (std::uint32_t i = 1; i < kSize; ++i) {
      const float roughness = (j + 0.5f) / kSize, a = roughness * roughness, nv = (i + 0.5f) / kSize;
      const glm::vec3 v(std::sqrt(1.0f - nv * nv), 0.0f, nv);
      double sumA = 0.0, sumB = 0.0;
      const int nt = 400, np = 400;
      for (int it = 0; it < nt; ++it)
        for (int ip = 0; ip < np; ++ip) {
          const float theta = (it + 0.5f) / nt * 0.5f * kPi, phi = (ip + 0.5f) / np * 2.0f * kPi;
          const glm::vec3 l(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
          const glm::vec3 h = glm::normalize(v + l);
          const float t = h.z * h.z * (a * a - 1.0f) + 1.0f;
          const float d = a * a / (kPi * t * t);
          const float g = 1.0f / (1.0f + lambda(nv, a) + lambda(l.z, a));
          const float fcos = d * g / (4.0f * nv);  // f cos without Fresnel
          const float fc = std::pow(1.0f - glm::dot(v, h), 5.0f);
          const double dw = std::sin(theta) * (0.5 * kPi / nt) * (2.0 * kPi / np);
          sumA += (1.0f - fc) * fcos * dw;
          sumB += fc * fcos * dw;
        }
      const glm::vec2 got = table[j * kSize + i];
      EXPECT_NEAR(got.x, sumA, 0.01 * (sumA + sumB)) << "n.v " << nv << " roughness " << roughness;
      EXPECT_NEAR(got.y, sumB, 0.01 * (sumA + sumB)) << "n.v " << nv << " roughness " << roughness;
      ++checked;
    }
  EXPECT_EQ(checked, 35);
  // A smooth surface loses nothing to shadowing: A + B is 1.
  const std::vector<glm::vec2> smooth = splitSumTable(64, 1024);
  const glm::vec2 ab = smooth[0 * 64 + 40];
  EXPECT_NEAR(ab.x + ab.y, 1.0f, 0.01f);
}

// E_avg of the multiple-scattering term: 1 for a table that loses nothing,
// and less the rougher the row (rough GGX loses more to shadowing).
TEST(VulkanGltfMaterial, AverageAlbedoFallsWithRoughness) {
  constexpr std::uint32_t kSize = 16;
  const std::vector<float> lossless = averageAlbedoByRow(std::vector<glm::vec2>(kSize * kSize, {1.0f, 0.0f}), kSize);
  for (float e : lossless) EXPECT_NEAR(e, 1.0f, 1e-6f);
  const std::vector<float> average = averageAlbedoByRow(splitSumTable(kSize, 1024), kSize);
  EXPECT_GT(average.front(), 0.95f);
  for (std::uint32_t j = 1; j < kSize; ++j) EXPECT_LT(average[j], average[j - 1] + 1e-3f) << "row " << j;
  // The hemispherical quadrature of the same D and G2 at roughness ~1 gives about 0.41.
  EXPECT_NEAR(average.back(), 0.41f, 0.04f);
}

// White furnace: white diffuse (metallic 0) and white metal spheres, rough
// and smoother, under a uniform environment L and no lights reflect L
// everywhere, within 5 % (the bound for the rasterizer).
TEST(VulkanGltfMaterial, WhiteFurnace) {
  const float L = 0.7f;
  for (float metallic : {0.0f, 1.0f})
    for (float roughness : {0.3f, 0.6f, 1.0f}) {
      Scene scene(device());
      scene.setEnvironment(Environment::constant(glm::vec3(L)));
      scene.addInstance(scene.addMesh(test::uvSphere(32, 64)),
                        scene.addMaterial(gltf(glm::vec3(1.0f), metallic, roughness)), glm::mat4(1.0f));
      Renderer renderer(device());
      FrameBuffer fb(64, 64);
      renderer.render(scene, Camera::lookAt({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 0.8f, 1.0f), Region::full(64, 64), fb);
      test::writePng("/tmp/tsr_vk_furnace.png", fb);
      int checked = 0;
      float worst = 0.0f;
      for (int y = 1; y < 63; ++y)
        for (int x = 1; x < 63; ++x) {
          bool inside = true;  // all neighbours on the sphere: no silhouette pixels
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) inside = inside && fb.colour(x + dx, y + dy).a == 1.0f;
          if (!inside) continue;
          for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(fb.colour(x, y)[c] - L) / L);
          ++checked;
        }
      EXPECT_GT(checked, 1000);
      EXPECT_LT(worst, 0.05f) << "metallic " << metallic << " roughness " << roughness;
    }
}

// An 8x1 normal map, linear: the left half flat, the right half bent.
TextureId bentHalf(Scene& scene, std::uint8_t r, std::uint8_t g) {
  std::vector<std::uint8_t> texels;
  for (int x = 0; x < 8; ++x) {
    const bool bent = x >= 4;
    texels.insert(texels.end(), {std::uint8_t(bent ? r : 128), std::uint8_t(bent ? g : 128), 255, 255});
  }
  return scene.addTexture(Texture::fromRgba8(8, 1, texels, false));
}

// A normal map bends shading where it is bent, by the amount and towards
// the side it says (+x along u, +y up the image), and leaves the rest.
TEST(VulkanGltfMaterial, NormalMapBendsShadingWhereItIsBentOnly) {
  const Camera cam = Camera::lookAt({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 0.8f, 1.0f);
  const Region full = Region::full(64, 64);
  struct Case {
    std::uint8_t r, g;
    glm::vec3 towardsLight;
  };
  for (const Case& k : {Case{218, 128, {1, 0, 0}}, Case{128, 218, {0, 1, 0}}}) {
    const glm::vec3 wi = glm::normalize(k.towardsLight + glm::vec3(0, 0, 1));
    auto render = [&](bool mapped) {
      Scene scene(device());
      Material m;
      m.baseColor = glm::vec3(0.8f);
      if (mapped) m.normalTexture = bentHalf(scene, k.r, k.g);
      scene.addInstance(scene.addMesh(test::quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0})), scene.addMaterial(m),
                        glm::mat4(1.0f));
      scene.addLight(DirectionalLight{-wi, glm::vec3(3.0f), false});
      Renderer renderer(device());
      FrameBuffer fb(64, 64);
      renderer.render(scene, cam, full, fb);
      return fb;
    };
    const FrameBuffer plain = render(false), mapped = render(true);
    test::writePng("/tmp/tsr_vk_normal_map.png", mapped);
    glm::vec3 bent((k.r / 255.0f) * 2.0f - 1.0f, (k.g / 255.0f) * 2.0f - 1.0f, 1.0f);
    bent = glm::normalize(bent);
    int flat = 0, changed = 0;
    for (float u = 0.1f; u < 0.95f; u += 0.05f)
      for (float v = 0.2f; v < 0.85f; v += 0.1f) {
        if (u > 0.43f && u < 0.57f) continue;  // the bilinear seam
        const glm::vec2 px = test::project(cam, full, {2.0f * u - 1.0f, 1.0f - 2.0f * v, 0.0f});
        const float a = plain.colour(int(px.x), int(px.y)).g, b = mapped.colour(int(px.x), int(px.y)).g;
        if (u < 0.5f) {
          EXPECT_NEAR(b, a, 0.005f * a) << "flat half changed at u " << u;  // 128 is 0.004 off flat
          ++flat;
        } else {
          const float expected = 0.8f / kPi * 3.0f * glm::dot(bent, wi);
          EXPECT_NEAR(b, expected, 0.01f * expected) << "bent half at u " << u;
          EXPECT_GT(b, a * 1.1f);  // bent towards the light
          ++changed;
        }
      }
    EXPECT_GT(flat, 20);
    EXPECT_GT(changed, 20);
  }
}

// A specular highlight widens and dims as roughness goes from 0.2 to 1: the
// area above half its peak grows and the peak falls, monotonically.
TEST(VulkanGltfMaterial, RoughnessWidensTheHighlightMonotonically) {
  const Camera cam = Camera::lookAt({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 1.2f, 1.0f);
  float lastArea = 0.0f, lastPeak = std::numeric_limits<float>::infinity();
  // Below about 0.2 the lobe of a point light is narrower than a pixel here.
  for (float roughness : {0.2f, 0.3f, 0.45f, 0.6f, 0.8f, 1.0f}) {
    Scene scene(device());
    // Black: only the dielectric specular (F0 0.04) shows.
    scene.addInstance(scene.addMesh(test::quad({-6, -6, 0}, {6, -6, 0}, {6, 6, 0}, {-6, 6, 0})),
                      scene.addMaterial(gltf(glm::vec3(0.0f), 0.0f, roughness)), glm::mat4(1.0f));
    scene.addLight(PointLight{{0.0f, 0.0f, 2.0f}, glm::vec3(50.0f)});
    Renderer renderer(device());
    FrameBuffer fb(128, 128);
    renderer.render(scene, cam, Region::full(128, 128), fb);
    float peak = 0.0f;
    for (const glm::vec4& c : fb.colourImage()) peak = std::max(peak, c.g);
    float area = 0.0f;
    for (const glm::vec4& c : fb.colourImage()) area += c.g >= 0.5f * peak ? 1.0f : 0.0f;
    EXPECT_GT(area, lastArea) << "roughness " << roughness;
    EXPECT_LT(peak, lastPeak) << "roughness " << roughness;
    EXPECT_LT(area, 128.0f * 128.0f) << "the half-peak region fits the image";
    lastArea = area;
    lastPeak = peak;
  }
}

// Image-based lighting: under an environment red above the horizon and blue
// below, a mirror sphere seen from the side shows red near its top and blue
// near its bottom; a rough metal sphere mixes them (its reflection is
// prefiltered by roughness), so its top is less red than the mirror's.
TEST(VulkanGltfMaterial, EnvironmentReflectionsArePrefilteredByRoughness) {
  std::vector<glm::vec4> texels(16 * 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) texels[y * 16 + x] = y < 4 ? glm::vec4(1, 0, 0, 1) : glm::vec4(0, 0, 1, 1);
  const Environment sky = Environment::latLong(16, 8, texels);
  const Camera cam = Camera::lookAt({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 0.8f, 1.0f);
  const Region full = Region::full(64, 64);
  auto render = [&](const Material& m) {
    Scene scene(device());
    scene.setEnvironment(sky);
    scene.addInstance(scene.addMesh(test::uvSphere(32, 64)), scene.addMaterial(m), glm::mat4(1.0f));
    Renderer renderer(device());
    FrameBuffer fb(64, 64);
    renderer.render(scene, cam, full, fb);
    return fb;
  };
  Material mirror;
  mirror.type = MaterialType::Mirror;
  mirror.baseColor = glm::vec3(1.0f);
  const FrameBuffer sharp = render(mirror), rough = render(gltf(glm::vec3(1.0f), 1.0f, 0.8f));
  test::writePng("/tmp/tsr_vk_ibl_mirror.png", sharp);
  test::writePng("/tmp/tsr_vk_ibl_rough.png", rough);
  // Normals 20 degrees up and down: the mirrored directions point 40
  // degrees above and below the horizon, which a rough lobe reaches across.
  const glm::vec2 top = test::project(cam, full, glm::vec3(0, 0.342f, 0.94f));
  const glm::vec2 bottom = test::project(cam, full, glm::vec3(0, -0.342f, 0.94f));
  const glm::vec4 st = sharp.colour(int(top.x), int(top.y)), sb = sharp.colour(int(bottom.x), int(bottom.y));
  EXPECT_GT(st.r, 0.9f);
  EXPECT_LT(st.b, 0.05f);
  EXPECT_GT(sb.b, 0.9f);
  EXPECT_LT(sb.r, 0.05f);
  const glm::vec4 rt = rough.colour(int(top.x), int(top.y));
  EXPECT_GT(rt.r, rt.b) << "still mostly the sky above";
  EXPECT_LT(rt.r / (rt.r + rt.b), st.r / (st.r + st.b) - 0.05f) << "blurred towards the other half";
}

// KHR_texture_transform: a base colour texture red on its left half and
// blue on its right, shifted by half a repeat along u, shows blue on the
// quad's left and red on its right (and the identity shows it as it is).
TEST(VulkanGltfMaterial, TextureTransformMovesTheTexture) {
  const Camera cam = Camera::lookAt({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 0.8f, 1.0f);
  const Region full = Region::full(64, 64);
  for (const bool shifted : {false, true}) {
    Scene scene(device());
    std::vector<std::uint8_t> texels;
    for (int x = 0; x < 8; ++x)
      texels.insert(texels.end(), {std::uint8_t(x < 4 ? 255 : 0), 0, std::uint8_t(x < 4 ? 0 : 255), 255});
    Material m = gltf(glm::vec3(1.0f), 0.0f, 1.0f);
    m.baseColorTexture = scene.addTexture(Texture::fromRgba8(8, 1, texels, false));
    if (shifted) m.uv[std::size_t(TextureSlot::BaseColor)].row0 = glm::vec3(1.0f, 0.0f, 0.5f);
    scene.addInstance(scene.addMesh(test::quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0})), scene.addMaterial(m),
                      glm::mat4(1.0f));
    scene.setEnvironment(Environment::constant(glm::vec3(1.0f)));
    Renderer renderer(device());
    FrameBuffer fb(64, 64);
    renderer.render(scene, cam, full, fb);
    const glm::vec2 left = test::project(cam, full, {-0.5f, 0, 0}), right = test::project(cam, full, {0.5f, 0, 0});
    const glm::vec4 l = fb.colour(int(left.x), int(left.y)), r = fb.colour(int(right.x), int(right.y));
    EXPECT_EQ(l.r > l.b, !shifted) << "left, shifted " << shifted;
    EXPECT_EQ(r.b > r.r, !shifted) << "right, shifted " << shifted;
  }
}

// glTF's occlusion texture darkens the ambient and image-based light by
// 1 + strength (occlusion - 1), and leaves direct light alone.
TEST(VulkanGltfMaterial, OcclusionDarkensAmbientLightOnly) {
  const Camera cam = Camera::lookAt({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 0.8f, 1.0f);
  const Region full = Region::full(64, 64);
  auto render = [&](bool ambient, float strength) {
    Scene scene(device());
    Material m = gltf(glm::vec3(0.8f), 0.0f, 0.6f);
    if (strength >= 0.0f) {
      const std::uint8_t quarter[4] = {64, 64, 64, 255};  // 0.25, linear
      m.occlusionTexture = scene.addTexture(Texture::fromRgba8(1, 1, quarter, false));
      m.occlusionStrength = strength;
    }
    scene.addInstance(scene.addMesh(test::quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0})), scene.addMaterial(m),
                      glm::mat4(1.0f));
    if (ambient)
      scene.setEnvironment(Environment::constant(glm::vec3(1.0f)));
    else
      scene.addLight(DirectionalLight{glm::normalize(glm::vec3(0.3f, 0.2f, -1.0f)), glm::vec3(2.0f), false});
    Renderer renderer(device());
    FrameBuffer fb(64, 64);
    renderer.render(scene, cam, full, fb);
    return fb.colour(32, 32);
  };
  const float occlusion = 64.0f / 255.0f;
  const glm::vec4 open = render(true, -1.0f), occluded = render(true, 1.0f), half = render(true, 0.5f);
  EXPECT_NEAR(occluded.g, occlusion * open.g, 0.01f * open.g);
  EXPECT_NEAR(half.g, (1.0f + 0.5f * (occlusion - 1.0f)) * open.g, 0.01f * open.g);
  const glm::vec4 lit = render(false, -1.0f), litOccluded = render(false, 1.0f);
  EXPECT_GT(lit.g, 0.05f);
  EXPECT_NEAR(litOccluded.g, lit.g, 1e-4f) << "direct light is not occluded";
}

}  // namespace
}  // namespace tsr::vk
