// Compact vertex streams: the stated tolerance holds for positions and
// normals over many values, zero normals survive, and a mesh's box grows
// when a vertex edit leaves it (white box: src/scene/vertex_encoding.hpp).
#include "scene/vertex_encoding.hpp"
#include "scene/uv_density.hpp"
#include "test_util.hpp"

#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <random>
#include <vector>

namespace tsr::vk {
namespace {

TEST(VertexEncoding, PositionsMoveByAtMostHalfAStepOfTheirBox) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  // A long thin mesh far from the origin: each axis has its own step.
  std::vector<glm::vec3> positions(20000);
  for (auto& p : positions) p = glm::vec3(1000.0f + 200.0f * u(rng), 0.05f * u(rng), -30.0f + 3.0f * u(rng));
  const PositionQuantization q = PositionQuantization::of(positions);
  const glm::vec3 halfStep = q.scale() / 131070.0f;
  // Half a step, plus the float rounding of the decoding (a few ulp of the box's corners).
  glm::vec3 bound;
  for (int a = 0; a < 3; ++a) {
    const float m = std::max(std::abs(q.lo[a]), std::abs(q.hi[a]));
    bound[a] = halfStep[a] + 4.0f * (std::nextafter(m, INFINITY) - m);
  }
  for (const auto& p : positions) {
    const glm::vec3 back = dequantize(q, quantize(q, p));
    for (int a = 0; a < 3; ++a) ASSERT_LE(std::abs(back[a] - p[a]), bound[a]) << a;
  }
  // The box's corners are exact, and a flat axis is its one value.
  const glm::vec3 flat[2] = {{1, 2, 3}, {4, 2, 6}};
  const PositionQuantization f = PositionQuantization::of(flat);
  EXPECT_EQ(dequantize(f, quantize(f, flat[0])), flat[0]);
  EXPECT_EQ(dequantize(f, quantize(f, flat[1])), flat[1]);
}

TEST(VertexEncoding, UvsMoveByAtMostHalfAStepOfTheirBox) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  // A texture repeated 16 times one way, once the other.
  std::vector<glm::vec2> uvs(20000);
  for (auto& uv : uvs) uv = glm::vec2(-8.0f + 16.0f * u(rng), u(rng));
  const UvQuantization q = UvQuantization::of(uvs);
  for (const auto& uv : uvs) {
    const glm::vec2 back = dequantize(q, quantize(q, uv));
    ASSERT_LE(std::abs(back.x - uv.x), 16.0f / 131070.0f + 4e-6f);
    ASSERT_LE(std::abs(back.y - uv.y), 1.0f / 131070.0f + 4e-7f);
  }
}

TEST(VertexEncoding, NormalsTurnByAtMostAHundredthOfADegreeAndZeroStaysZero) {
  std::mt19937 rng(11);
  std::normal_distribution<float> g;
  float worst = 0.0f;
  for (int i = 0; i < 100000; ++i) {
    const glm::vec3 n = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
    const glm::vec3 back = octDecode(octEncode(n));
    // The angle from the cross product: acos near 1 is too coarse in float.
    worst = std::max(worst, std::atan2(glm::length(glm::cross(n, back)), glm::dot(n, back)));
  }
  EXPECT_LT(worst * 180.0f / 3.14159265f, 0.01f);
  // The poles and axes, and the direction whose code is next to the reserved corner.
  for (const glm::vec3 n : {glm::vec3(0, 0, -1), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), glm::vec3(0, -1, 0),
                            glm::normalize(glm::vec3(-1e-6f, -1e-6f, -1))}) {
    EXPECT_NE(octEncode(n), kNoNormal);
    EXPECT_GT(glm::dot(octDecode(octEncode(n)), n), 0.99999f);
  }
  EXPECT_EQ(octEncode(glm::vec3(0.0f)), kNoNormal);
  EXPECT_EQ(octDecode(kNoNormal), glm::vec3(0.0f));
  // Length does not matter: a normal is a direction.
  EXPECT_EQ(octEncode(glm::vec3(0, 3, 4)), octEncode(glm::vec3(0, 0.6f, 0.8f)));
}

// Vertex edits that change the mesh's box (out beyond it, then back in)
// leave the mesh drawn exactly as a fresh mesh of the same positions: the
// box follows the exact positions, so no edit history shows.
TEST(VertexEncoding, EditsThatMoveTheBoxDrawAsAFreshMesh) {
  const Camera cam = Camera::lookAt({0, 3, 6}, {0, 0, 0}, {0, 1, 0}, 0.9f, 1.0f);
  auto render = [&](Scene& scene) {
    Renderer r(test::device(), RenderSettings{});
    FrameBuffer fb(64, 64);
    r.render(scene, cam, Region::full(64, 64), fb);
    return fb;
  };
  const MeshData sphere = test::uvSphere(16, 24, 0.8f);
  auto build = [&](Scene& scene, const MeshData& mesh) {
    scene.addLight(DirectionalLight{{0.3f, -1, -0.2f}, glm::vec3(2.0f)});
    const MeshId m = scene.addMesh(mesh);
    scene.addInstance(m, scene.addMaterial({}), glm::mat4(1.0f));
    return m;
  };
  auto fresh = [&](const MeshData& mesh) {
    Scene scene(test::device());
    build(scene, mesh);
    return render(scene);
  };
  Scene edited(test::device());
  const MeshId m = build(edited, sphere);
  const FrameBuffer before = render(edited);
  // Pull a band of vertices out to twice the radius: beyond the box.
  const std::uint32_t first = 100, count = 40;
  MeshData pulled = sphere;
  for (std::uint32_t i = first; i < first + count; ++i) pulled.positions[i] *= 2.0f;
  edited.updateMeshVertices(m, {.positions = pulled.positions, .first = first, .count = count});
  const FrameBuffer out = render(edited);
  EXPECT_GT(test::maxAbsDiff(before, out), 0.1f) << "the edit shows";
  EXPECT_EQ(out.colourImage(), fresh(pulled).colourImage());
  EXPECT_EQ(out.depthImage(), fresh(pulled).depthImage());
  // Then part of the band back in (the box shrinks again), in two edits.
  MeshData back = pulled;
  for (std::uint32_t i = first; i < first + count; ++i) back.positions[i] = sphere.positions[i] * 1.3f;
  edited.updateMeshVertices(m, {.positions = back.positions, .first = first, .count = count / 2});
  edited.updateMeshVertices(m, {.positions = back.positions, .first = first + count / 2, .count = count / 2});
  const FrameBuffer in = render(edited);
  EXPECT_EQ(in.colourImage(), fresh(back).colourImage());
  EXPECT_EQ(in.depthImage(), fresh(back).depthImage());
  // And all the way back: the first image again.
  edited.updateMeshVertices(m, {.positions = sphere.positions, .first = first, .count = count});
  EXPECT_EQ(render(edited).colourImage(), before.colourImage());
}

// The level of detail's density: a 2x2 square mapped to the unit uv square
// holds half a uv unit a length unit; scaled uvs scale it, uvs stretched
// unevenly give the mean, and a mesh without uvs or area has none.
TEST(VulkanUvDensity, MeanUvUnitsALengthUnit) {
  const std::vector<glm::vec3> square{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
  const std::vector<std::uint32_t> two{0, 1, 2, 0, 2, 3};
  EXPECT_FLOAT_EQ(uvDensity(square, std::vector<glm::vec2>{{0, 0}, {1, 0}, {1, 1}, {0, 1}}, two), 0.5f);
  EXPECT_FLOAT_EQ(uvDensity(square, std::vector<glm::vec2>{{0, 0}, {4, 0}, {4, 4}, {0, 4}}, two), 2.0f);
  // uv areas 2 and 1 over areas 2 and 2.
  EXPECT_FLOAT_EQ(uvDensity(square, std::vector<glm::vec2>{{0, 0}, {2, 0}, {2, 2}, {0, 1}}, two),
                  std::sqrt(3.0f / 4.0f));
  EXPECT_EQ(uvDensity(square, {}, two), 0.0f);
  EXPECT_EQ(uvDensity(std::vector<glm::vec3>(4, glm::vec3(1)), std::vector<glm::vec2>(4), two), 0.0f);
}

}  // namespace
}  // namespace tsr::vk
