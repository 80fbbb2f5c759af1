#include "tsr/med/light_translation.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

using namespace tsr;

TEST(LightTranslation, LightsArePlacedByTheirWorldMatrix) {
  sg::Scene s;
  auto& light = s.create<sg::Light>();
  light.setKind(sg::LightKind::Spot);
  light.setColor({1, 0.5f, 0.25f});
  light.setIntensity(8);
  glm::mat4 world = glm::translate(glm::mat4(1.0f), glm::vec3(1, 2, 3)) *
                    glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(0, 1, 0));
  const backend::Light translated = med::translateLight(light, world);
  const auto* spot = std::get_if<backend::SpotLight>(&translated);
  ASSERT_NE(spot, nullptr);
  EXPECT_EQ(spot->position, glm::vec3(1, 2, 3));
  EXPECT_NEAR(spot->direction.x, -1.0f, 1e-6f) << "-Z turned 90 degrees about Y";
  EXPECT_EQ(spot->intensity, glm::vec3(8, 4, 2));
  EXPECT_EQ(spot->innerAngle, light.innerConeAngle());
  EXPECT_EQ(spot->outerAngle, light.outerConeAngle());
}

TEST(LightTranslation, KindsKeepWhatTheyUse) {
  sg::Scene s;
  auto& light = s.create<sg::Light>();
  light.setKind(sg::LightKind::Directional);
  light.setIntensity(2);
  const glm::mat4 world = glm::translate(glm::mat4(1.0f), glm::vec3(5, 0, 0));
  const backend::Light sunLight = med::translateLight(light, world);
  const auto* sun = std::get_if<backend::DirectionalLight>(&sunLight);
  ASSERT_NE(sun, nullptr);
  EXPECT_EQ(sun->direction, glm::normalize(light.direction())) << "a translation does not turn it";
  EXPECT_EQ(sun->irradiance, light.color() * 2.0f);
  light.setKind(sg::LightKind::Point);
  const backend::Light pointLight = med::translateLight(light, world);
  const auto* point = std::get_if<backend::PointLight>(&pointLight);
  ASSERT_NE(point, nullptr);
  EXPECT_EQ(point->position, glm::vec3(world * glm::vec4(light.position(), 1.0f)));
}
