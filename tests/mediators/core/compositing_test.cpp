#include "tsr/med/compositing.hpp"

#include <gtest/gtest.h>

#include "tsr/med/image_file.hpp"

using namespace tsr::med;

namespace {
FrameBuffer filled(glm::vec4 c, float depth) {
  FrameBuffer fb(2, 1);
  for (auto& p : fb.colour) p = c;
  for (auto& d : fb.depth) d = depth;
  return fb;
}
}  // namespace

TEST(Compositing, NearerLayerWinsWhateverTheOrder) {
  FrameBuffer base = filled({1, 0, 0, 1}, 5.0f);
  FrameBuffer layer = filled({0, 0, 1, 1}, 3.0f);
  layer.depth[1] = 7.0f;  // behind the base at pixel 1
  compositeByDepth(base, layer);
  EXPECT_EQ(base.colour[0], glm::vec4(0, 0, 1, 1));
  EXPECT_EQ(base.depth[0], 3.0f);
  EXPECT_EQ(base.colour[1], glm::vec4(1, 0, 0, 1)) << "occluded by the base";
  EXPECT_EQ(base.depth[1], 5.0f);
}

TEST(Compositing, AlphaBlendsAndEmptyPixelsShowWhatIsBehind) {
  FrameBuffer base = filled({0, 0, 1, 1}, 10.0f);
  FrameBuffer layer = filled({1, 0, 0, 0.25f}, 2.0f);
  layer.colour[1] = glm::vec4(0.3f, 0.3f, 0.3f, 0.0f);  // nothing drawn here
  layer.depth[1] = kNoDepth;
  compositeByDepth(base, layer);
  EXPECT_NEAR(base.colour[0].r, 0.25f, 1e-6f);
  EXPECT_NEAR(base.colour[0].b, 0.75f, 1e-6f);
  EXPECT_EQ(base.colour[1], glm::vec4(0, 0, 1, 1));
  EXPECT_EQ(base.depth[1], 10.0f);
}

TEST(Compositing, AnaglyphTakesRedFromTheLeftEye) {
  FrameBuffer left = filled({0.9f, 0.1f, 0.1f, 1}, 1), right = filled({0.2f, 0.6f, 0.7f, 1}, 1);
  FrameBuffer out = anaglyph(left, right);
  EXPECT_EQ(out.colour[0], glm::vec4(0.9f, 0.6f, 0.7f, 1));
  EXPECT_EQ(sideBySide(left, right).width, 4u);
  EXPECT_THROW(anaglyph(left, FrameBuffer(3, 3)), std::invalid_argument);
}

TEST(Compositing, DuboisProjectsBothEyesAndClamps) {
  // The matrices' rows add up to about 1: white seen by both eyes stays white.
  FrameBuffer white = filled({1, 1, 1, 1}, 1), black = filled({0, 0, 0, 1}, 1);
  FrameBuffer whiteOut = anaglyph(white, white, AnaglyphMethod::Dubois);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(whiteOut.colour[0][c], 1.0f, 2e-3f) << c;
  // Left eye red alone: the red filter passes 0.456 of it; negative parts clamp to 0.
  FrameBuffer red = filled({1, 0, 0, 1}, 1);
  EXPECT_EQ(anaglyph(red, black, AnaglyphMethod::Dubois).colour[0], glm::vec4(0.4561f, 0, 0, 1));
  // Right eye blue alone: 1.2264 of it, clamped.
  FrameBuffer blue = filled({0, 0, 1, 1}, 1);
  EXPECT_EQ(anaglyph(black, blue, AnaglyphMethod::Dubois).colour[0], glm::vec4(0, 0, 1, 1));
  // Green in the left eye darkens the cyan channels (the cross-talk term).
  FrameBuffer green = filled({0, 1, 0, 1}, 1), grey = filled({0.5f, 0.5f, 0.5f, 1}, 1);
  FrameBuffer out = anaglyph(green, grey, AnaglyphMethod::Dubois);
  EXPECT_NEAR(out.colour[0].g, 0.5f * (0.378476f + 0.73364f - 0.0184503f) - 0.0378246f, 1e-5f);
  EXPECT_EQ(anaglyph(green, grey, AnaglyphMethod::RedCyan).colour[0], glm::vec4(0, 0.5f, 0.5f, 1));
}

TEST(ImageFile, ExrKeepsFloatsAndPngIsEncoded) {
  FrameBuffer fb(3, 2);
  for (std::size_t i = 0; i < fb.colour.size(); ++i) fb.colour[i] = glm::vec4(0.1f * float(i), 2.5f, 0.5f, 1.0f);
  auto dir = ::testing::TempDir();
  writeImage(dir + "/t.exr", fb);
  FrameBuffer exr = readImage(dir + "/t.exr");
  ASSERT_EQ(exr.width, 3u);
  for (std::size_t i = 0; i < fb.colour.size(); ++i) EXPECT_EQ(exr.colour[i], fb.colour[i]);
  writeImage(dir + "/t.png", fb);
  FrameBuffer png = readImage(dir + "/t.png");
  EXPECT_NEAR(png.colour[1].r, 0.1f, 0.01f);
  EXPECT_FLOAT_EQ(png.colour[1].g, 1.0f) << "clamped";
  EXPECT_THROW(writeImage(dir + "/t.nosuchformat", fb), ImageFileError);
  EXPECT_THROW(writeImage(dir + "/t.png", fb, "albedo"), ImageFileError);
  EXPECT_THROW(readImage(dir + "/missing.png"), ImageFileError);
}
