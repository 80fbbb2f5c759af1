#include "test_scenes.hpp"

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <thread>

namespace tsr::embree::test {
namespace {

struct Fixture {
  Scene scene{sharedDevice()};
  Camera camera;
  MaterialId material;
  Fixture() {
    camera = cornellBox(scene, 0);
    material = scene.addMaterial({});
  }
};

TEST(EmbreeProgressive, AccumulatesAndRestartsOnlyOnChange) {
  Fixture f;
  RenderSettings s;
  s.samplesPerPass = 2;
  Renderer renderer(s);
  Region region = Region::full(16, 16);
  FrameBuffer fb(16, 16);
  EXPECT_TRUE(renderer.renderPass(f.scene, f.camera, region, fb).restarted);
  EXPECT_FALSE(renderer.renderPass(f.scene, f.camera, region, fb).restarted);
  EXPECT_EQ(fb.sampleCount(3, 4), 4u);

  RenderSettings threads = s;
  threads.threads = 1;
  threads.tileSize = 3;
  renderer.setSettings(threads);  // does not affect the image
  EXPECT_FALSE(renderer.renderPass(f.scene, f.camera, region, fb).restarted);
  EXPECT_EQ(fb.sampleCount(3, 4), 6u);

  Camera moved = f.camera;
  moved.cameraToWorld = glm::translate(moved.cameraToWorld, glm::vec3(1, 0, 0));
  EXPECT_TRUE(renderer.renderPass(f.scene, moved, region, fb).restarted);
  EXPECT_EQ(fb.sampleCount(3, 4), 2u);

  f.scene.addLight(PointLight{{100, 100, 100}, glm::vec3(10)});
  EXPECT_TRUE(renderer.renderPass(f.scene, moved, region, fb).restarted);

  RenderSettings depth = threads;
  depth.maxDepth = 2;
  renderer.setSettings(depth);
  EXPECT_TRUE(renderer.renderPass(f.scene, moved, region, fb).restarted);
}

TEST(EmbreeProgressive, CancelStopsThePassAndLeavesPixelsConsistent) {
  Fixture f;
  Renderer renderer;
  Region region = Region::full(16, 16);
  FrameBuffer fb(16, 16);
  renderer.requestCancel();
  PassResult r = renderer.renderPass(f.scene, f.camera, region, fb);
  EXPECT_FALSE(r.completed);
  for (std::uint32_t y = 0; y < 16; ++y)
    for (std::uint32_t x = 0; x < 16; ++x) EXPECT_EQ(fb.sampleCount(x, y), 0u);
  EXPECT_TRUE(renderer.renderPass(f.scene, f.camera, region, fb).completed);

  // Cancel from another thread while a long pass runs.
  RenderSettings slow;
  slow.samplesPerPass = 4096;
  renderer.setSettings(slow);
  FrameBuffer big(64, 64);
  std::thread canceller([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    renderer.requestCancel();
  });
  r = renderer.renderPass(f.scene, f.camera, Region::full(64, 64), big);
  canceller.join();
  EXPECT_FALSE(r.completed);
  std::uint32_t done = 0;
  for (std::uint32_t y = 0; y < 64; ++y)
    for (std::uint32_t x = 0; x < 64; ++x) {
      std::uint32_t n = big.sampleCount(x, y);
      EXPECT_TRUE(n == 0 || n == 4096);
      done += n ? 1 : 0;
    }
  EXPECT_LT(done, 64u * 64u);
}

TEST(EmbreeProgressive, CountsEveryRay) {
  Fixture f;
  RenderSettings s;
  s.maxDepth = 0;  // camera rays only
  s.samplesPerPass = 3;
  Renderer renderer(s);
  FrameBuffer fb(10, 10);
  PassResult r = renderer.renderPass(f.scene, f.camera, Region::full(10, 10), fb);
  EXPECT_EQ(r.rays, 300u);
  s.maxDepth = 1;  // plus one shadow ray per lit hit and one bounce ray per surviving path
  renderer.setSettings(s);
  r = renderer.renderPass(f.scene, f.camera, Region::full(10, 10), fb);
  EXPECT_GT(r.rays, 600u);
  EXPECT_LE(r.rays, 900u);
  EXPECT_EQ(renderer.totalRays(), 300u + r.rays);
}

TEST(EmbreeProgressive, VarianceShrinksAndChannelsAddUp) {
  Fixture f;
  RenderSettings s;
  s.samplesPerPass = 8;
  Renderer renderer(s);
  FrameBuffer fb(8, 8);
  render(renderer, f.scene, f.camera, Region::full(8, 8), fb, 4);
  for (std::uint32_t y = 0; y < 8; ++y)
    for (std::uint32_t x = 0; x < 8; ++x) {
      glm::vec3 sum = fb.mean(Channel::Direct, x, y) + fb.mean(Channel::Indirect, x, y);
      glm::vec3 c = fb.mean(Channel::Colour, x, y);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(sum[k], c[k], 1e-4f * (1.0f + c[k]));
      EXPECT_TRUE(std::isfinite(fb.depth(x, y)));
    }
  // Above the blocks the camera sees the back wall, 800 + 559.2 units along
  // the view axis, facing the camera.
  EXPECT_NEAR(fb.depth(4, 2), 800.0f + 559.2f, 0.05f);
  EXPECT_NEAR(fb.normal(4, 2).z, -1.0f, 1e-5f);
  EXPECT_EQ(fb.albedo(4, 2), glm::vec3(1.0f));
}

}  // namespace
}  // namespace tsr::embree::test
