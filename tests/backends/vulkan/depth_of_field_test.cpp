// The rasterizer's thin lens (src/post/depth_of_field.hpp): what lies in
// the focus plane stays sharp, what lies far behind it spreads over a disk
// keeping its light, a flat image stays flat, and crops of the image (a
// wall's tiles) blur exactly as the whole image does.
#include "test_util.hpp"

#include "post/depth_of_field.hpp"
#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"

#include <gtest/gtest.h>

namespace tsr::vk {
namespace {

using test::device;
using test::glowing;

constexpr std::uint32_t kSize = 64;

Camera lensCamera(float aperture, float aspect = 1.0f) {
  Camera c = Camera::lookAt({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 0.8f, aspect);
  c.apertureRadius = aperture;
  c.focusDistance = 5.0f;  // the plane z = 0
  return c;
}

// A red square in focus on the left, a green one far behind on the right.
struct Planes {
  Scene scene{device()};
  Planes() {
    scene.addInstance(
        scene.addMesh(test::quad({-1.6f, -0.5f, 0}, {-0.6f, -0.5f, 0}, {-0.6f, 0.5f, 0}, {-1.6f, 0.5f, 0})),
        scene.addMaterial(glowing({1, 0, 0})), glm::mat4(1.0f));
    scene.addInstance(scene.addMesh(test::quad({2, -3, -20}, {8, -3, -20}, {8, 3, -20}, {2, 3, -20})),
                      scene.addMaterial(glowing({0, 1, 0})), glm::mat4(1.0f));
  }
  FrameBuffer render(const Camera& camera, const Region& region = Region::full(kSize, kSize)) {
    Renderer renderer(device());
    FrameBuffer fb(region.regionWidth(), region.regionHeight());
    renderer.render(scene, camera, region, fb);
    return fb;
  }
};

TEST(VulkanDepthOfField, InFocusSharpFarBlurredItsLightKept) {
  Planes p;
  const FrameBuffer pinhole = p.render(lensCamera(0.0f));
  const FrameBuffer lens = p.render(lensCamera(0.5f));
  // The blur of a point 25 units away: 0.5 * 20 / 25 at the focus plane, 15 pixels a unit there.
  EXPECT_NEAR(blurRadius(lensCamera(0.5f), blurPixelsPerUnit(lensCamera(0.5f), Region::full(kSize, kSize)), 25.0f),
              6.0f, 0.1f);
  double greenPinhole = 0, greenLens = 0;
  std::size_t spreadPinhole = 0, spreadLens = 0, sharpDiffer = 0, sharpPixels = 0;
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      greenPinhole += pinhole.colour(x, y).g;
      greenLens += lens.colour(x, y).g;
      spreadPinhole += pinhole.colour(x, y).g > 0.01f;
      spreadLens += lens.colour(x, y).g > 0.01f;
      if (x < kSize / 2 && pinhole.colour(x, y).r > 0.0f) {  // the red square, far from the green's blur
        ++sharpPixels;
        sharpDiffer += lens.colour(x, y) != pinhole.colour(x, y);
      }
    }
  EXPECT_GT(sharpPixels, 30u);
  EXPECT_LE(sharpDiffer, sharpPixels / 3) << "only the square's edge, where the dark background's blur reaches";
  EXPECT_GT(spreadLens, spreadPinhole + 20) << "the far square spreads";
  EXPECT_NEAR(greenLens, greenPinhole, 0.1 * greenPinhole) << "and keeps its light";
  EXPECT_EQ(lens.depthImage(), pinhole.depthImage());
}

TEST(VulkanDepthOfField, AFlatImageStaysFlat) {
  const Camera camera = lensCamera(0.5f);
  const Region full = Region::full(40, 30);
  std::vector<glm::vec4> colour(full.pixelCount(), glm::vec4(0.25f, 0.5f, 0.75f, 1.0f));
  std::vector<float> depth(full.pixelCount());
  for (std::size_t i = 0; i < depth.size(); ++i) depth[i] = 1.0f + float(i % 17);  // blurs from none to much
  const std::vector<glm::vec4> before = colour;
  applyDepthOfField(camera, full, colour, depth);
  for (std::size_t i = 0; i < colour.size(); ++i)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(colour[i][c], before[i][c], 1e-5f);
}

// Crops away from the image's edges and off the 8-pixel tile grid: each is
// drawn with its margin and blurred on its own, and equals the whole
// image's pixels.
TEST(VulkanDepthOfField, TilesBlurAsTheWholeImage) {
  Planes p;
  const std::uint32_t w = 200, h = 150;
  const Camera camera = lensCamera(0.5f, float(w) / float(h));
  const FrameBuffer whole = p.render(camera, Region::full(w, h));
  const Region tiles[] = {
      {w, h, 61, 53, 133, 101}, {w, h, 0, 0, 61, 53}, {w, h, 133, 101, w, h}, {w, h, 97, 5, 150, 60}};
  for (const Region& tile : tiles) {
    const FrameBuffer part = p.render(camera, tile);
    std::size_t differ = 0;
    for (std::uint32_t y = 0; y < tile.regionHeight(); ++y)
      for (std::uint32_t x = 0; x < tile.regionWidth(); ++x)
        differ += part.colour(x, y) != whole.colour(tile.x0 + x, tile.y0 + y) ||
                  part.depth(x, y) != whole.depth(tile.x0 + x, tile.y0 + y);
    EXPECT_EQ(differ, 0u) << "tile at " << tile.x0 << ", " << tile.y0;
  }
}

TEST(VulkanDepthOfField, OffLeavesThePinholeImage) {
  Planes p;
  RenderSettings off;
  off.depthOfField = false;
  Renderer renderer(device(), off);
  FrameBuffer fb(kSize, kSize);
  renderer.render(p.scene, lensCamera(0.5f), Region::full(kSize, kSize), fb);
  EXPECT_EQ(fb.colourImage(), p.render(lensCamera(0.0f)).colourImage());
}

}  // namespace
}  // namespace tsr::vk
