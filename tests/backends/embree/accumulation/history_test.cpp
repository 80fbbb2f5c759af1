// Temporal reprojection (FrameBuffer::reproject through the renderer): a
// view change keeps what the samples knew of the surfaces still in view,
// and nothing of what is no longer there.
#include "test_scenes.hpp"

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <tuple>

namespace tsr::embree::test {
namespace {

constexpr std::uint32_t kSize = 48;

// A red box before a grey wall, in a constant sky, seen from the origin.
struct BoxBeforeWall {
  Scene scene{sharedDevice()};
  Camera camera = Camera::lookAt({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, glm::radians(60.0f), 1.0f);
  InstanceId wall, box;
  BoxBeforeWall() {
    Material grey, red;
    grey.baseColor = glm::vec3(0.9f);
    red.baseColor = glm::vec3(0.9f, 0.0f, 0.0f);
    wall = scene.addInstance(scene.addMesh(quad({-6, -6, -5}, {6, -6, -5}, {6, 6, -5}, {-6, 6, -5})),
                             scene.addMaterial(grey), glm::mat4(1.0f));
    box = scene.addInstance(scene.addMesh(test::box({-0.5f, -0.5f, -2.5f}, {0.5f, 0.5f, -1.5f})),
                            scene.addMaterial(red), glm::mat4(1.0f));
    scene.setEnvironment(Environment::constant(glm::vec3(0.5f)));
  }
};

RenderSettings withHistory(std::uint32_t limit = 16) {
  RenderSettings s;
  s.historyLimit = limit;
  s.samplesPerPass = 16;
  return s;
}

// The scene rendered once at 16 spp with the history on; later passes of
// one sample (frames).
struct Rendered : BoxBeforeWall {
  Renderer renderer{withHistory()};
  const Region region = Region::full(kSize, kSize);
  FrameBuffer fb{kSize, kSize};
  FrameBuffer before{kSize, kSize};
  Rendered() {
    renderer.renderPass(scene, camera, region, fb);
    before = fb;
    RenderSettings one = withHistory();
    one.samplesPerPass = 1;
    renderer.setSettings(one);
  }
};

// The object every sample of an 8-spp render of the view sees, per pixel
// (kNoObject where they disagree): the pixels inside one surface.
std::vector<std::uint32_t> solidObjects(Scene& scene, const Camera& camera) {
  RenderSettings s;
  s.samplesPerPass = 1;
  Renderer renderer(s);
  FrameBuffer fb(kSize, kSize);
  const Region region = Region::full(kSize, kSize);
  std::vector<std::uint32_t> objects(std::size_t(kSize) * kSize, kNoObject);
  renderer.renderPass(scene, camera, region, fb);
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) objects[y * kSize + x] = fb.object(x, y);
  for (int pass = 1; pass < 8; ++pass) {
    FrameBuffer one(kSize, kSize);
    RenderSettings seeded = s;
    seeded.seed = std::uint64_t(pass);
    renderer.setSettings(seeded);
    renderer.renderPass(scene, camera, region, one);
    for (std::uint32_t y = 0; y < kSize; ++y)
      for (std::uint32_t x = 0; x < kSize; ++x)
        if (one.object(x, y) != objects[y * kSize + x]) objects[y * kSize + x] = kNoObject - 1;
  }
  // Shrunk by a pixel: a pixel counts as inside when its neighbours agree.
  std::vector<std::uint32_t> inside(objects.size(), kNoObject - 1);
  for (std::uint32_t y = 1; y + 1 < kSize; ++y)
    for (std::uint32_t x = 1; x + 1 < kSize; ++x) {
      bool same = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) same = same && objects[(y + dy) * kSize + x + dx] == objects[y * kSize + x];
      if (same) inside[y * kSize + x] = objects[y * kSize + x];
    }
  return inside;
}

TEST(EmbreeHistory, AWholePixelPanMovesTheImageByThosePixels) {
  BoxBeforeWall f;
  Renderer renderer(withHistory());
  const Region region = Region::full(kSize, kSize);
  FrameBuffer fb(kSize, kSize);
  renderer.renderPass(f.scene, f.camera, region, fb);
  const FrameBuffer before = fb;
  // The window slides 3 pixels to the right: what pixel x + 3 showed, x shows.
  constexpr std::uint32_t kShift = 3;
  Camera panned = f.camera;
  const float step = (panned.right - panned.left) / float(kSize) * float(kShift);
  panned.left += step;
  panned.right += step;
  EXPECT_TRUE(renderer.restartIfStale(f.scene, panned, region, fb));
  EXPECT_TRUE(fb.carriesHistory());
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      SCOPED_TRACE(::testing::Message() << "pixel " << x << ", " << y);
      if (x + kShift >= kSize) {
        EXPECT_EQ(fb.sampleCount(x, y), 0u) << "came into view: nothing to carry";
        continue;
      }
      ASSERT_EQ(fb.inheritedCount(x, y), 16u);
      EXPECT_EQ(fb.tracedCount(x, y), 0u);
      const glm::vec4 a = fb.colour(x, y), b = before.colour(x + kShift, y);
      for (int c = 0; c < 4; ++c) EXPECT_NEAR(a[c], b[c], 1e-4f * (1.0f + std::abs(b[c])));
      EXPECT_EQ(fb.object(x, y), before.object(x + kShift, y));
      EXPECT_NEAR(fb.depth(x, y), before.depth(x + kShift, y), 1e-4f);
    }
}

TEST(EmbreeHistory, CarriedSamplesAreCappedAtTheLimit) {
  BoxBeforeWall f;
  Renderer renderer(withHistory(12));
  const Region region = Region::full(kSize, kSize);
  FrameBuffer fb(kSize, kSize);
  test::render(renderer, f.scene, f.camera, region, fb, 3);  // 48 spp
  Camera moved = f.camera;
  moved.cameraToWorld = glm::translate(moved.cameraToWorld, glm::vec3(0.05f, 0, 0));
  renderer.restartIfStale(f.scene, moved, region, fb);
  std::size_t carried = 0;
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      EXPECT_TRUE(fb.inheritedCount(x, y) == 0 || fb.inheritedCount(x, y) == 12u) << x << ", " << y;
      carried += fb.inheritedCount(x, y) > 0;
    }
  EXPECT_GT(carried, kSize * kSize * 3 / 4);
}

// One sample a frame while the camera keeps moving: the samples add up to
// the limit, and the limit holds.
TEST(EmbreeHistory, OneSampleAFrameAddsUpToTheLimit) {
  BoxBeforeWall f;
  RenderSettings s = withHistory(16);
  s.samplesPerPass = 1;
  Renderer renderer(s);
  const Region region = Region::full(kSize, kSize);
  FrameBuffer fb(kSize, kSize);
  Camera camera = f.camera;
  for (int frame = 0; frame < 24; ++frame) {
    camera.cameraToWorld = glm::rotate(camera.cameraToWorld, glm::radians(0.3f), glm::vec3(0, 1, 0));
    renderer.renderPass(f.scene, camera, region, fb);
  }
  std::size_t full = 0;
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      EXPECT_LE(fb.sampleCount(x, y), 17u);
      EXPECT_EQ(fb.tracedCount(x, y), 1u);
      full += fb.sampleCount(x, y) == 17u;
    }
  EXPECT_GT(full, kSize * kSize / 2) << "most pixels hold the limit and the frame's sample";
}

TEST(EmbreeHistory, DisoccludedPixelsDoNotKeepWhatHidThem) {
  Rendered f;
  auto [renderer, region, fb, before] = std::tie(f.renderer, f.region, f.fb, f.before);
  Camera moved = f.camera;
  moved.cameraToWorld = glm::translate(moved.cameraToWorld, glm::vec3(0.6f, 0, 0));
  renderer.renderPass(f.scene, moved, region, fb);
  const auto solid = solidObjects(f.scene, moved);
  const std::uint32_t wall = std::uint32_t(f.wall), box = std::uint32_t(f.box);
  std::size_t revealed = 0, carried = 0;
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      carried += fb.inheritedCount(x, y) > 0;
      if (solid[y * kSize + x] != wall) continue;
      revealed += before.object(x, y) == box;
      // The box's red albedo would show in the wall's green.
      EXPECT_NEAR(fb.albedo(x, y).g, 0.9f, 1e-4f) << "wall pixel " << x << ", " << y << " holds the box's samples";
    }
  EXPECT_GT(revealed, 20u) << "the move shows wall where the box stood";
  EXPECT_GT(carried, kSize * kSize / 2) << "the rest keeps its history";
}

TEST(EmbreeHistory, AMovedObjectLeavesNoTrailAndTakesItsSamplesAlong) {
  Rendered f;
  auto [renderer, region, fb, before] = std::tie(f.renderer, f.region, f.fb, f.before);
  f.scene.setInstanceTransform(f.box, glm::translate(glm::mat4(1.0f), glm::vec3(0.8f, 0, 0)));
  const auto solid = solidObjects(f.scene, f.camera);
  const std::uint32_t wall = std::uint32_t(f.wall), box = std::uint32_t(f.box);
  for (int frame = 0; frame < 2; ++frame) renderer.renderPass(f.scene, f.camera, region, fb);
  std::size_t left = 0, boxPixels = 0, boxCarried = 0;
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      const std::uint32_t now = solid[y * kSize + x];
      if (now == wall && before.object(x, y) == box) {
        ++left;
        EXPECT_NEAR(fb.albedo(x, y).g, 0.9f, 1e-4f) << "a trail of the box at " << x << ", " << y;
      }
      if (now == box) {
        ++boxPixels;
        boxCarried += fb.inheritedCount(x, y) > 0;
      }
    }
  EXPECT_GT(left, 20u) << "the box left pixels behind";
  EXPECT_GT(boxCarried, boxPixels * 3 / 4) << "the box's own pixels follow it with their samples";
}

// The first new sample of a pixel checks what reproject() predicted there:
// told that the box moved when it did not, the pixels where it was predicted
// see the wall and drop what they inherited.
TEST(EmbreeHistory, APredictionTheFirstSampleRefutesIsDropped) {
  Rendered f;
  auto [renderer, region, fb, before] = std::tie(f.renderer, f.region, f.fb, f.before);
  const std::vector<glm::mat4> then(2, glm::mat4(1.0f));
  std::vector<glm::mat4> told = then;
  told[std::uint32_t(f.box)] = glm::translate(glm::mat4(1.0f), glm::vec3(0.8f, 0, 0));
  fb.reproject({f.camera, f.camera, region, region, then, told, 16});
  std::vector<std::uint32_t> predictedBox;
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x)
      if (fb.inheritedCount(x, y) > 0 && fb.object(x, y) == std::uint32_t(f.box) &&
          before.object(x, y) == std::uint32_t(f.wall))
        predictedBox.push_back(y * kSize + x);
  ASSERT_GT(predictedBox.size(), 20u) << "the box carried to where it was said to be";
  // The renderer sees an unchanged key: the pass adds to what reproject() left.
  EXPECT_FALSE(renderer.renderPass(f.scene, f.camera, region, fb).restarted);
  const auto solid = solidObjects(f.scene, f.camera);
  std::size_t checked = 0;
  for (std::uint32_t i : predictedBox) {
    const std::uint32_t x = i % kSize, y = i / kSize;
    if (solid[i] != std::uint32_t(f.wall)) continue;  // near an edge: a sample may find the box after all
    ++checked;
    EXPECT_EQ(fb.inheritedCount(x, y), 0u) << x << ", " << y;
    EXPECT_EQ(fb.sampleCount(x, y), 1u) << x << ", " << y;
  }
  EXPECT_GT(checked, 20u);
}

TEST(EmbreeHistory, AnEditOtherThanAMoveDropsTheHistory) {
  BoxBeforeWall f;
  Renderer renderer(withHistory());
  const Region region = Region::full(kSize, kSize);
  FrameBuffer fb(kSize, kSize);
  renderer.renderPass(f.scene, f.camera, region, fb);
  f.scene.setEnvironment(Environment::constant(glm::vec3(0.8f, 0.5f, 0.5f)));  // the sky's colour: what lights all
  EXPECT_TRUE(renderer.restartIfStale(f.scene, f.camera, region, fb));
  EXPECT_FALSE(fb.carriesHistory());
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) ASSERT_EQ(fb.sampleCount(x, y), 0u);
}

TEST(EmbreeHistory, AStillCameraRendersTheSameBitsWithHistoryOnOrOff) {
  BoxBeforeWall f;
  const Region region = Region::full(kSize, kSize);
  RenderSettings off;
  off.samplesPerPass = 3;
  RenderSettings on = off;
  on.historyLimit = 16;
  Renderer a(off), b(on);
  FrameBuffer fa(kSize, kSize), fbuf(kSize, kSize);
  test::render(a, f.scene, f.camera, region, fa, 3);
  test::render(b, f.scene, f.camera, region, fbuf, 3);
  EXPECT_TRUE(test::identical(fa, fbuf));
  EXPECT_FALSE(fbuf.carriesHistory());
}

}  // namespace
}  // namespace tsr::embree::test
