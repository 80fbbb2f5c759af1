// rankObjects from a hand-made id output, and the id encoding's limits.
#include <gtest/gtest.h>

#include <cmath>

#include "tsr/med/coverage/ranking.hpp"

using namespace tsr;

TEST(IdOutput, EncodingIsExactBeyondFloatIntegers) {
  for (sg::ContainerId id :
       {sg::ContainerId{1}, sg::ContainerId{(1u << 24) - 1}, sg::ContainerId{1u << 24},
        sg::ContainerId{(1ull << 24) + 1}, sg::ContainerId{123456789012ull}, sg::ContainerId{(1ull << 48) - 1}}) {
    EXPECT_EQ(med::decodeObjectId(med::encodeObjectId(id)), id) << id;
  }
  EXPECT_EQ(med::encodeObjectId(77).r, 77.0f) << "small ids are the red channel";
  EXPECT_EQ(med::decodeObjectId(glm::vec4(0.0f)), sg::kNoContainer);
  EXPECT_THROW(med::encodeObjectId(1ull << 48), std::invalid_argument);
  EXPECT_THROW(med::decodeObjectId(glm::vec4(1.5f, 0, 0, 1)), std::invalid_argument);
  EXPECT_THROW(med::decodeObjectId(glm::vec4(-1.0f, 0, 0, 1)), std::invalid_argument);
  EXPECT_THROW(med::decodeObjectId(glm::vec4(NAN, 0, 0, 1)), std::invalid_argument);
}

TEST(RankObjects, CountsSortsAndNames) {
  sg::Scene scene;
  auto& a = scene.create<sg::Transform>("alpha");
  auto& b = scene.create<sg::Transform>();
  auto& g = scene.create<sg::Geometry>("beta mesh");
  b.addChild(g.id());
  med::FrameBuffer fb(4, 2);
  auto& out = fb.outputs[med::kIdOutput];
  const sg::ContainerId gone = 999;
  for (sg::ContainerId id : {a.id(), b.id(), b.id(), gone, a.id(), b.id(), sg::kNoContainer, sg::kNoContainer})
    out.push_back(med::encodeObjectId(id));
  auto ranking = med::rankObjects(fb, scene);
  ASSERT_EQ(ranking.size(), 3u);
  EXPECT_EQ(ranking[0], (med::RankedObject{b.id(), "beta mesh", 3, 3.0 / 8}));
  EXPECT_EQ(ranking[1], (med::RankedObject{a.id(), "alpha", 2, 2.0 / 8}));
  EXPECT_EQ(ranking[2], (med::RankedObject{gone, "", 1, 1.0 / 8}));
  EXPECT_EQ(med::backgroundPixels(fb), 2u);
}

TEST(RankObjects, RefusesFrameBuffersWithoutIds) {
  sg::Scene scene;
  med::FrameBuffer fb(2, 2);
  EXPECT_THROW(med::rankObjects(fb, scene), std::invalid_argument);
  fb.outputs[med::kIdOutput].resize(3);
  EXPECT_THROW(med::rankObjects(fb, scene), std::invalid_argument);
}
