#include "test_util.hpp"

#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"

#include <gtest/gtest.h>

#include <cstring>

namespace tsr::vk {
namespace {

using test::device;
using test::glowing;

// A closed axis-aligned box, faces wound counter-clockwise seen from outside.
MeshData box(glm::vec3 lo, glm::vec3 hi) {
  MeshData m;
  auto face = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    MeshData q = test::quad(a, b, c, d);
    const auto base = std::uint32_t(m.positions.size());
    m.positions.insert(m.positions.end(), q.positions.begin(), q.positions.end());
    m.normals.insert(m.normals.end(), q.normals.begin(), q.normals.end());
    m.uvs.insert(m.uvs.end(), q.uvs.begin(), q.uvs.end());
    for (std::uint32_t i : q.indices) m.indices.push_back(base + i);
  };
  const float x0 = lo.x, y0 = lo.y, z0 = lo.z, x1 = hi.x, y1 = hi.y, z1 = hi.z;
  face({x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1});  // +z
  face({x1, y0, z0}, {x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0});  // -z
  face({x1, y0, z1}, {x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1});  // +x
  face({x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0});  // -x
  face({x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0}, {x0, y1, z0});  // +y
  face({x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1});  // -y
  return m;
}

// A medium with an index-matched boundary (glass of ior 1: no reflection).
Material medium(glm::vec3 absorption, glm::vec3 scattering = glm::vec3(0.0f)) {
  Material m;
  m.type = MaterialType::Glass;
  m.ior = 1.0f;
  m.roughness = 0.0f;
  m.interior = Medium{absorption, scattering, glm::vec3(0.0f), 0.0f};
  return m;
}

const Camera kCam = Camera::lookAt({0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 0.8f, 1.0f);
const Region kFull = Region::full(64, 64);

struct Variant {
  std::uint32_t samples;
  Visibility visibility;
};
const Variant kVariants[] = {{1, Visibility::All}, {4, Visibility::All}, {1, Visibility::Guided}};

// The emitters here are what is seen through the medium, not lights: they
// neither light it nor add to the ambient term, so the figures are analytic.
RenderSettings analytic(const Variant& v) {
  return {.msaaSamples = v.samples, .visibility = v.visibility, .emitterLights = 0, .emitterAmbient = false};
}

// Behind a slab of thickness d seen head-on, a white emitter keeps
// exp(-sigma_a d) per channel. The tolerance, 0.5 % relative, covers the
// thickness reconstructed from 32-bit depth (about 1e-4 here) and a
// half-float colour target where the device picks one.
TEST(VulkanVolume, AbsorbingSlabTransmitsBeerLambert) {
  const glm::vec3 sigma(0.2f, 0.5f, 1.0f);
  for (const Variant& v : kVariants) {
    glm::vec3 previous(1.0f);
    for (float d : {0.25f, 0.5f, 1.0f, 2.0f}) {
      Scene scene(device());
      scene.addInstance(scene.addMesh(test::quad({-3, -3, -2}, {3, -3, -2}, {3, 3, -2}, {-3, 3, -2})),
                        scene.addMaterial(glowing(glm::vec3(1.0f))), glm::mat4(1.0f));
      scene.addInstance(scene.addMesh(box({-1, -1, -d / 2}, {1, 1, d / 2})), scene.addMaterial(medium(sigma)),
                        glm::mat4(1.0f));
      Renderer renderer(device(), analytic(v));
      FrameBuffer fb(64, 64);
      renderer.render(scene, kCam, kFull, fb);
      test::writePng("/tmp/tsr_vk_volume_slab.png", fb);
      const glm::vec4 c = fb.colour(32, 32);
      for (int ch = 0; ch < 3; ++ch) {
        const float expected = std::exp(-sigma[ch] * d);
        EXPECT_NEAR(c[ch], expected, 0.005f * expected) << "d " << d << " channel " << ch << " samples " << v.samples;
        EXPECT_LT(c[ch], previous[ch]) << "thicker must be darker, d " << d;
        previous[ch] = c[ch];
      }
      // Outside the slab the emitter is untouched.
      EXPECT_NEAR(fb.colour(2, 32).r, 1.0f, 1e-3f);
      // The medium writes no depth: depth is the emitter's.
      EXPECT_NEAR(fb.depth(32, 32), 6.0f, 1e-3f);
    }
  }
}

// Opaque geometry inside the medium ends the view ray there: an emitter
// half-way through a slab of depth 2 loses exp(-sigma 1), not exp(-sigma 2).
TEST(VulkanVolume, OpaqueGeometryInsideEndsTheRay) {
  const float sigma = 0.7f;
  Scene scene(device());
  scene.addInstance(scene.addMesh(test::quad({-0.5f, -0.5f, 0}, {0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}, {-0.5f, 0.5f, 0})),
                    scene.addMaterial(glowing(glm::vec3(1.0f))), glm::mat4(1.0f));
  scene.addInstance(scene.addMesh(box({-1, -1, -1}, {1, 1, 1})), scene.addMaterial(medium(glm::vec3(sigma))),
                    glm::mat4(1.0f));
  Renderer renderer(device(), analytic({1, Visibility::All}));
  FrameBuffer fb(64, 64);
  renderer.render(scene, kCam, kFull, fb);
  EXPECT_NEAR(fb.colour(32, 32).g, std::exp(-sigma), 0.005f * std::exp(-sigma));
}

// A purely scattering medium (albedo 1) under a constant environment L and
// nothing behind: it shows L (1 - T) scattered in, with T = exp(-sigma_s d).
TEST(VulkanVolume, ScatteringSlabShowsAmbientScatteredIn) {
  const float sigma = 0.8f, d = 1.0f, L = 0.6f;
  Scene scene(device());
  scene.setEnvironment(Environment::constant(glm::vec3(L)));
  scene.addInstance(scene.addMesh(test::quad({-3, -3, -2}, {3, -3, -2}, {3, 3, -2}, {-3, 3, -2})),
                    scene.addMaterial(glowing(glm::vec3(0.0f))), glm::mat4(1.0f));
  scene.addInstance(scene.addMesh(box({-1, -1, -d / 2}, {1, 1, d / 2})),
                    scene.addMaterial(medium(glm::vec3(0.0f), glm::vec3(sigma))), glm::mat4(1.0f));
  Renderer renderer(device(), analytic({1, Visibility::All}));
  FrameBuffer fb(64, 64);
  renderer.render(scene, kCam, kFull, fb);
  const float expected = L * (1.0f - std::exp(-sigma * d));
  EXPECT_NEAR(fb.colour(32, 32).r, expected, 0.005f * expected);
}

// Scene fog: a surface at distance t sends its radiance times T = exp(-sigma_t t)
// plus the ambient scattered in, L sigma_s / sigma_t (1 - T); where nothing is
// drawn only that in-scattered light remains. Far emitters are greyer than near ones.
TEST(VulkanVolume, FogGreysFarMoreThanNear) {
  const Medium fog{glm::vec3(0.1f), glm::vec3(0.1f), glm::vec3(0.0f), 0.0f};
  const float L = 0.5f;
  const float haze = L * 0.1f / 0.2f;
  const Camera cam = Camera::lookAt({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 1.0f, 1.0f, 0.05f, 100.0f);
  for (const Variant& v : kVariants) {
    Scene scene(device());
    scene.setEnvironment(Environment::constant(glm::vec3(L)).withFog(fog));
    const MeshId q = scene.addMesh(test::quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}));
    const MaterialId white = scene.addMaterial(glowing(glm::vec3(1.0f)));
    scene.addInstance(q, white, glm::translate(glm::mat4(1.0f), {-0.8f, 0, -2}));  // near, left
    scene.addInstance(q, white, glm::translate(glm::mat4(1.0f), {2.4f, 0, -8}));   // far, right
    Renderer renderer(device(), analytic(v));
    FrameBuffer fb(64, 64);
    renderer.render(scene, cam, kFull, fb);
    test::writePng("/tmp/tsr_vk_fog.png", fb);
    int checked = 0;
    for (const glm::vec3 p : {glm::vec3(-0.8f, 0.3f, -2), glm::vec3(2.4f, 0.3f, -8)}) {
      const glm::vec2 px = test::project(cam, kFull, p);
      const glm::vec3 seen = test::pixelOnPlane(cam, kFull, int(px.x), int(px.y), {0, 0, 1}, p.z);
      const float t = glm::length(seen);
      const float T = std::exp(-0.2f * t);
      const float expected = T + haze * (1.0f - T);
      EXPECT_NEAR(fb.colour(int(px.x), int(px.y)).g, expected, 0.005f) << "distance " << t;
      ++checked;
    }
    EXPECT_EQ(checked, 2);
    const glm::vec2 nearPx = test::project(cam, kFull, {-0.8f, 0, -2}),
                    farPx = test::project(cam, kFull, {2.4f, 0, -8});
    EXPECT_GT(fb.colour(int(nearPx.x), int(nearPx.y)).r, fb.colour(int(farPx.x), int(farPx.y)).r + 0.3f);
    // Nothing drawn at the top: only the haze.
    EXPECT_NEAR(fb.colour(32, 1).b, haze, 1e-5f);
  }
}

// A medium the rasterizer cannot show (behind an opaque surface), an empty
// medium and an empty fog leave the image bit for bit as without them.
TEST(VulkanVolume, UnshownOrEmptyMediaChangeNoBit) {
  auto render = [](bool withMedia) {
    Scene scene(device());
    Environment env = Environment::constant(glm::vec3(0.2f));
    scene.setEnvironment(withMedia ? env.withFog(Medium{}) : env);
    scene.addLight(PointLight{{1, 2, 3}, glm::vec3(8.0f)});
    Material diffuse;
    diffuse.baseColor = {0.7f, 0.4f, 0.2f};
    Material glass;
    glass.type = MaterialType::Glass;
    if (withMedia) {
      diffuse.interior = Medium{glm::vec3(1.0f), glm::vec3(1.0f), glm::vec3(0.0f), 0.3f};
      glass.interior = Medium{};
    }
    const MeshId sphere = scene.addMesh(test::uvSphere(16, 32, 0.8f));
    scene.addInstance(sphere, scene.addMaterial(diffuse), glm::translate(glm::mat4(1.0f), {-0.9f, 0, 0}));
    scene.addInstance(sphere, scene.addMaterial(glass), glm::translate(glm::mat4(1.0f), {0.9f, 0, 0}));
    Renderer renderer(device());
    FrameBuffer fb(64, 64);
    renderer.render(scene, kCam, kFull, fb);
    return fb;
  };
  const FrameBuffer a = render(false), b = render(true);
  ASSERT_EQ(a.colourImage().size(), b.colourImage().size());
  EXPECT_EQ(std::memcmp(a.colourImage().data(), b.colourImage().data(), a.colourImage().size() * sizeof(glm::vec4)), 0);
  EXPECT_GT(a.colour(16, 32).r, 0.05f);  // the spheres were drawn
}

TEST(VulkanVolume, RefusesInvalidMedia) {
  Scene scene(device());
  Material m = medium(glm::vec3(-1.0f));
  EXPECT_THROW(scene.addMaterial(m), Error);
  m = medium(glm::vec3(1.0f));
  m.interior->g = 1.0f;
  EXPECT_THROW(scene.addMaterial(m), Error);
  EXPECT_THROW(Environment().withFog(Medium{glm::vec3(NAN), glm::vec3(0.0f), glm::vec3(0.0f), 0.0f}), Error);
}

// A medium thick enough to hide what is behind it (optical depth 1 or
// more across its thinnest side) shadows the floor under a light as a
// solid would; a thin one casts no shadow. Seen from the side, the floor
// under the hovering box against the floor beside it.
TEST(VulkanVolume, DenseMediaCastShadowsThinOnesNone) {
  const Camera slant = Camera::lookAt({2.5f, 1.0f, 0}, {0, 0, 0}, {0, 1, 0}, 0.8f, 1.0f);
  auto shadowed = [&](float extinction) {
    Scene scene(device());
    Material floor;
    floor.baseColor = glm::vec3(0.8f);
    scene.addInstance(scene.addMesh(test::groundQuad(0, 0, 2.0f)), scene.addMaterial(floor), glm::mat4(1.0f));
    scene.addInstance(scene.addMesh(box({-0.25f, 0.5f, -0.25f}, {0.25f, 1.0f, 0.25f})),
                      scene.addMaterial(medium(glm::vec3(extinction))), glm::mat4(1.0f));
    scene.addLight(DirectionalLight{{0, -1, 0}, glm::vec3(3.0f)});
    Renderer renderer(device(), {.emitterAmbient = false});
    FrameBuffer fb(64, 64);
    renderer.render(scene, slant, kFull, fb);
    // The floor under the box (its shadow, seen below the box from the
    // side) against the floor at the same depth beside it.
    const glm::vec2 under = test::project(slant, kFull, {0.0f, 0.0f, 0.0f});
    const glm::vec2 beside = test::project(slant, kFull, {0.0f, 0.0f, 1.0f});
    return fb.colour(int(under.x), int(under.y)).g / fb.colour(int(beside.x), int(beside.y)).g;
  };
  EXPECT_LT(shadowed(8.0f), 0.5f) << "optical depth 4: a shadow";
  EXPECT_NEAR(shadowed(0.5f), 1.0f, 1e-3f) << "optical depth 0.25: none";
}

}  // namespace
}  // namespace tsr::vk
