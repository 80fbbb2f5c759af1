// A region holds exactly the ids and depths of the same crop of the full image.
#include <gtest/gtest.h>

#include "test_scenes.hpp"

using namespace tsr::cov;

TEST(Region, RenderEqualsCropOfFull) {
  EmbreeIdRenderer r;
  test::load(r, test::randomScene(5, 250, 60));
  Camera camera = test::straightCamera();
  camera.left = -1.3f;  // off-axis, as a wall tile's window would be
  const Region full = Region::full(150, 90);
  IdBuffer whole = r.render(camera, full);
  for (Region part : {Region{150, 90, 13, 5, 77, 61}, Region{150, 90, 149, 89, 150, 90}, Region{150, 90, 0, 0, 150, 1},
                      Region{150, 90, 64, 32, 96, 64}}) {
    IdBuffer crop = r.render(camera, part);
    ASSERT_EQ(crop.ids.size(), part.pixelCount());
    std::size_t differ = 0;
    for (std::uint32_t y = 0; y < crop.height(); ++y)
      for (std::uint32_t x = 0; x < crop.width(); ++x) {
        const std::size_t w = whole.index(part.x0 + x, part.y0 + y);
        differ += crop.id(x, y) != whole.ids[w];
        differ += crop.depth[crop.index(x, y)] != whole.depth[w];
      }
    EXPECT_EQ(differ, 0u) << "region " << part.x0 << "," << part.y0 << " " << part.x1 << "," << part.y1;
  }
}
