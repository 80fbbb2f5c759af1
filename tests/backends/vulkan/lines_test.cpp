// Lines and points: one pixel wide, unlit (their material's colour as it
// is), hidden by what is in front, drawn the same with guided visibility,
// and counted by the id pass.
#include "test_util.hpp"

#include "tsr/vk/error.hpp"
#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

namespace tsr::vk {
namespace {

using test::device;

constexpr std::uint32_t kSize = 32;
// Looking down -Z from z = 5.
const Camera kCam = Camera::lookAt({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 0.8f, 1.0f);
const glm::vec3 kInk(1.0f, 0.5f, 0.25f);

MeshData segments(std::vector<glm::vec3> positions, std::vector<std::uint32_t> indices, Primitive primitive) {
  MeshData m;
  m.positions = std::move(positions);
  m.indices = std::move(indices);
  m.primitive = primitive;
  return m;
}

struct Drawing {
  Scene scene{device()};
  MaterialId ink = [this] {
    Material m;
    m.baseColor = kInk;
    return scene.addMaterial(m);
  }();
  // A horizontal line across the middle, a vertical one, three points; lit by
  // a light that would shade a surface.
  Drawing() {
    scene.addInstance(scene.addMesh(segments({{-1, 0.05f, 0}, {1, 0.05f, 0}, {0.6f, -1, 0}, {0.6f, 1, 0}}, {0, 1, 2, 3},
                                             Primitive::Lines)),
                      ink, glm::mat4(1.0f));
    scene.addInstance(
        scene.addMesh(segments({{-0.6f, 0.6f, 0}, {-0.6f, -0.6f, 0}, {0.07f, -0.6f, 0}}, {0, 1, 2}, Primitive::Points)),
        ink, glm::mat4(1.0f));
    scene.addLight(DirectionalLight{{0.2f, -1, -0.4f}, glm::vec3(3.0f)});
  }
};

// Pixels that are not background.
std::vector<glm::uvec2> drawn(const FrameBuffer& fb) {
  std::vector<glm::uvec2> out;
  for (std::uint32_t y = 0; y < fb.height(); ++y)
    for (std::uint32_t x = 0; x < fb.width(); ++x)
      if (fb.colour(x, y).a > 0.0f) out.emplace_back(x, y);
  return out;
}

TEST(VulkanLines, OnePixelWideAndUnlit) {
  Drawing d;
  Renderer renderer(device());
  FrameBuffer fb(kSize, kSize);
  renderer.render(d.scene, kCam, Region::full(kSize, kSize), fb);
  const std::vector<glm::uvec2> pixels = drawn(fb);
  ASSERT_FALSE(pixels.empty()) << "lines and points drawn";
  for (const glm::uvec2& p : pixels) {
    const glm::vec4 c = fb.colour(p.x, p.y);
    EXPECT_NEAR(c.r, kInk.r, 1e-3f);
    EXPECT_NEAR(c.g, kInk.g, 1e-3f);
    EXPECT_NEAR(c.b, kInk.b, 1e-3f);
  }
  // The horizontal line: one pixel in each column it crosses (away from the vertical one).
  const glm::vec2 left = test::project(kCam, Region::full(kSize, kSize), {-1, 0.05f, 0});
  const glm::vec2 right = test::project(kCam, Region::full(kSize, kSize), {1, 0.05f, 0});
  const glm::vec2 vertical = test::project(kCam, Region::full(kSize, kSize), {0.6f, 0, 0});
  for (std::uint32_t x = std::uint32_t(left.x) + 1; x + 1 < std::uint32_t(right.x); ++x) {
    if (x + 1 >= std::uint32_t(vertical.x) && x <= std::uint32_t(vertical.x) + 1) continue;
    int inColumn = 0;
    for (const glm::uvec2& p : pixels) inColumn += p.x == x && std::abs(float(p.y) - left.y) < 3.0f;
    EXPECT_EQ(inColumn, 1) << "column " << x;
  }
  // Each point one pixel, where it projects.
  for (const glm::vec3& point : {glm::vec3(-0.6f, 0.6f, 0), glm::vec3(-0.6f, -0.6f, 0), glm::vec3(0.07f, -0.6f, 0)}) {
    const glm::vec2 at = test::project(kCam, Region::full(kSize, kSize), point);
    EXPECT_GT(fb.colour(std::uint32_t(at.x), std::uint32_t(at.y)).a, 0.0f) << point.x << ", " << point.y;
    int around = 0;
    for (const glm::uvec2& p : pixels)
      around += std::abs(float(p.x) - at.x) < 2.5f && std::abs(float(p.y) - at.y) < 2.5f;
    EXPECT_EQ(around, 1) << point.x << ", " << point.y;
  }
  for (const glm::uvec2& p : pixels) {
    if (p.x == std::uint32_t(left.x) + 3) {
      EXPECT_NEAR(fb.depth(p.x, p.y), 5.0f, 0.05f);
    }
  }
}

TEST(VulkanLines, HiddenBehindSurfacesAndEqualUnderGuidedVisibility) {
  Drawing d;
  // A wall in front of the drawing's right half.
  d.scene.addInstance(d.scene.addMesh(test::quad({0.2f, -2, 1}, {2, -2, 1}, {2, 2, 1}, {0.2f, 2, 1})),
                      d.scene.addMaterial({}), glm::mat4(1.0f));
  Renderer full(device());
  RenderSettings s;
  s.visibility = Visibility::Guided;
  Renderer guided(device(), s);
  FrameBuffer a(kSize, kSize), b(kSize, kSize);
  full.render(d.scene, kCam, Region::full(kSize, kSize), a);
  for (int frame = 0; frame < 2; ++frame) guided.render(d.scene, kCam, Region::full(kSize, kSize), b);
  EXPECT_EQ(a.colourImage(), b.colourImage());
  EXPECT_EQ(a.depthImage(), b.depthImage());
  const glm::vec2 hidden = test::project(kCam, Region::full(kSize, kSize), {0.6f, 0.5f, 0});
  const glm::vec2 shown = test::project(kCam, Region::full(kSize, kSize), {-0.6f, 0.6f, 0});  // a point
  EXPECT_NEAR(a.depth(std::uint32_t(hidden.x), std::uint32_t(hidden.y)), 4.0f, 0.05f) << "the wall, not the line";
  EXPECT_NEAR(a.colour(std::uint32_t(shown.x), std::uint32_t(shown.y)).r, kInk.r, 1e-3f);
}

TEST(VulkanLines, TheIdPassCountsThem) {
  Drawing d;
  const InstanceId line = d.scene.addInstance(
      d.scene.addMesh(segments({{-1, -0.3f, 0}, {1, -0.3f, 0}}, {0, 1}, Primitive::Lines)), d.ink, glm::mat4(1.0f));
  d.scene.setInstanceObject(line, 9);
  Renderer renderer(device());
  IdBuffer ids(kSize, kSize);
  renderer.renderIds(d.scene, kCam, Region::full(kSize, kSize), ids);
  std::size_t covered = 0;
  for (auto id : ids.ids) covered += id == 9u;
  // Two units wide at 7.6 pixels a unit: one pixel in each of 15 or 16 columns.
  EXPECT_GE(covered, 15u);
  EXPECT_LE(covered, 16u);
}

// Lines follow the opaque and the transparent instances in the draw order
// (the id pass: the opaque ones): each is drawn with its own transform and
// object id, whatever comes before it.
TEST(VulkanLines, DrawnWithTheirOwnPlaceAfterOpaqueAndTransparentInstances) {
  Scene scene(device());
  Material grey, glass, ink;
  glass.opacity = 0.5f;
  ink.baseColor = kInk;
  const MaterialId greyId = scene.addMaterial(grey), glassId = scene.addMaterial(glass), inkId = scene.addMaterial(ink);
  const MeshId square =
      scene.addMesh(test::quad({-0.3f, -0.3f, 0}, {0.3f, -0.3f, 0}, {0.3f, 0.3f, 0}, {-0.3f, 0.3f, 0}));
  for (float x : {-1.5f, -0.8f}) scene.addInstance(square, greyId, glm::translate(glm::mat4(1.0f), {x, 1.2f, 0}));
  scene.addInstance(square, glassId, glm::translate(glm::mat4(1.0f), {1.2f, 1.2f, 0}));
  // A short horizontal line drawn 1.1 below the centre by its transform.
  const InstanceId line =
      scene.addInstance(scene.addMesh(segments({{-0.5f, 0.05f, 0}, {0.5f, 0.05f, 0}}, {0, 1}, Primitive::Lines)), inkId,
                        glm::translate(glm::mat4(1.0f), {0, -1.1f, 0}));
  scene.setInstanceObject(line, 77);
  Renderer renderer(device());
  FrameBuffer fb(kSize, kSize);
  renderer.render(scene, kCam, Region::full(kSize, kSize), fb);
  IdBuffer ids(kSize, kSize);
  renderer.renderIds(scene, kCam, Region::full(kSize, kSize), ids);
  const glm::vec2 at = test::project(kCam, Region::full(kSize, kSize), {0, -1.05f, 0});
  int inked = 0, counted = 0;
  for (std::uint32_t y = std::uint32_t(at.y) - 2; y <= std::uint32_t(at.y) + 2; ++y) {
    inked += std::abs(fb.colour(std::uint32_t(at.x), y).r - kInk.r) < 1e-3f && fb.colour(std::uint32_t(at.x), y).a > 0;
    counted += ids.ids[ids.index(std::uint32_t(at.x), y)] == 77u;
  }
  EXPECT_EQ(inked, 1) << "the line where its transform puts it";
  EXPECT_EQ(counted, 1);
}

TEST(VulkanLines, IndexCountsMustFitThePrimitive) {
  Scene scene(device());
  EXPECT_THROW(scene.addMesh(segments({{0, 0, 0}, {1, 0, 0}}, {0, 1, 0}, Primitive::Lines)), Error);
  EXPECT_THROW(scene.addMesh(segments({{0, 0, 0}, {1, 0, 0}}, {0, 2}, Primitive::Lines)), Error);
  EXPECT_NO_THROW(scene.addMesh(segments({{0, 0, 0}, {1, 0, 0}}, {1}, Primitive::Points)));
}

}  // namespace
}  // namespace tsr::vk
