#include "tsr/med/scene_values.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

using namespace tsr;

TEST(SceneValues, TexelsAreLinearAndExpanded) {
  sg::Scene s;
  auto& img = s.create<sg::Image>();
  img.setPixels(2, 1, 2, sg::PixelFormat::UInt8, {255, 128, 188, 255});  // grey + alpha
  auto t = med::linearTexels(img);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_FLOAT_EQ(t[0].r, 1.0f);
  EXPECT_NEAR(t[0].a, 128.0f / 255.0f, 1e-6f) << "alpha is not sRGB-decoded";
  EXPECT_NEAR(t[1].g, 0.5f, 0.01f) << "sRGB 188 is about linear 0.5";
  img.setColorSpace(sg::ColorSpace::Linear);
  EXPECT_NEAR(med::linearTexels(img)[1].g, 188.0f / 255.0f, 1e-6f);
}

TEST(SceneValues, SurfaceClassesFollowTheThresholds) {
  sg::Scene s;
  auto& m = s.create<sg::SurfaceMaterial>();
  EXPECT_EQ(med::classify(m), med::SurfaceClass::Diffuse);
  m.setMetallic(1);
  m.setRoughness(0);
  EXPECT_EQ(med::classify(m), med::SurfaceClass::Mirror);
  m.setRoughness(0.3f);
  EXPECT_EQ(med::classify(m), med::SurfaceClass::Conductor);
  m.setTransmission(1);
  EXPECT_EQ(med::classify(m), med::SurfaceClass::Dielectric) << "transmission wins over metal";
  m.setRoughness(0);
  EXPECT_EQ(med::classify(m), med::SurfaceClass::Glass);
}

TEST(SceneValues, GradientRunsFromZenithToNadir) {
  sg::Scene s;
  auto& bg = s.create<sg::Background>();
  bg.setGradient({0, 0, 1}, {1, 0, 0});
  auto sky = med::bakeGradient(bg);
  ASSERT_EQ(sky.texels.size(), std::size_t{sky.width} * sky.height);
  EXPECT_GT(sky.texels.front().b, 0.95f);
  EXPECT_GT(sky.texels.back().r, 0.95f);
}
