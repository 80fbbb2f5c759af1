// visibility=guided through the Vulkan viewport on a small builtin:plant:
// after one frame from a view, the image equals visibility=all's bit for
// bit; an edited transform is drawn where it moved in the frame it moved.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "../viewport_rig.hpp"
#include "tsr/med/vulkan/register.hpp"
#include "vulkan_viewport.hpp"

using namespace tsr;

namespace {

constexpr std::uint32_t kWidth = 96, kHeight = 64;

med::Parameters guidedParameters() {
  med::Parameters p;
  p.set("visibility", std::string("guided"));
  return p;
}

struct Plant {
  test::ImportedScene scene{"vulkan", med::registerVulkan, "builtin:plant:40000"};
  test::Follower full, guided;

  Plant() {
    const auto snapshot = scene.source.commit();
    full.replica.apply(snapshot);
    guided.replica.apply(snapshot);
  }
  void publish() {
    const auto changes = scene.source.commit();
    full.replica.apply(changes);
    guided.replica.apply(changes);
  }
  med::View view(glm::vec3 eye, glm::vec3 target) const {
    med::View v = scene.view(scene.source, kWidth, kHeight);
    v.cameraToWorld = glm::inverse(glm::lookAt(eye, target, glm::vec3(0, 1, 0)));
    return v;
  }
  // One frame of each; the number of pixels that differ.
  std::size_t differing(const med::View& v) {
    render(full, scene.settings(), v);
    med::ViewportSettings s = scene.settings();
    s.parameters = guidedParameters();
    render(guided, s, v);
    return test::differingPixels(full.image, guided.image);
  }
  med::RenderStats lastGuided;

 private:
  void render(test::Follower& f, const med::ViewportSettings& s, const med::View& v) {
    if (!f.viewport) f.viewport = scene.registry.create(s, f.contexts);
    const med::RenderStats stats = f.viewport->render(f.replica, v, f.image);
    if (&f == &guided) lastGuided = stats;
  }
};

TEST(VulkanGuidedPlant, EqualsFullDrawAfterOneFrameOfEachView) {
  Plant p;
  const med::View inside = p.scene.view(p.scene.source, kWidth, kHeight);
  const med::View views[] = {inside, p.view({0, 40, -30}, {0, 0, 30}), p.view({-35, 4, 15}, {0, 3, 20}),
                             p.view({3, 6, 30}, {-10, 2, 0}), inside};
  for (const med::View& v : views) {
    EXPECT_EQ(p.differing(v), 0u) << "the first frame from a view";
    EXPECT_EQ(p.differing(v), 0u);
  }
  // Inside the plant most parts hide behind others.
  EXPECT_EQ(p.differing(inside), 0u);
  const auto drawn = [](const test::Follower& f) {
    return dynamic_cast<const med::vulkan_mediator::VulkanViewport&>(*f.viewport).lastFrame().objects;
  };
  EXPECT_LT(drawn(p.guided), drawn(p.full) / 2) << drawn(p.guided) << " of " << drawn(p.full);
}

TEST(VulkanGuidedPlant, MovedTransformIsDrawnWhereItMovedThatFrame) {
  Plant p;
  const med::View inside = p.scene.view(p.scene.source, kWidth, kHeight);
  p.differing(inside);
  ASSERT_EQ(p.differing(inside), 0u);
  // The last part of the plant, far from the aisle's start, moved in front of the camera.
  sg::ContainerId last = sg::kNoContainer;
  for (auto id : p.scene.source.ids())
    if (const auto* t = p.scene.source.find<sg::Transform>(id))
      for (auto child : t->children())
        if (p.scene.source.find<sg::Geometry>(child)) last = id;
  ASSERT_NE(last, sg::kNoContainer);
  const med::FrameBuffer before = p.guided.image;
  p.scene.source.find<sg::Transform>(last)->setMatrix(glm::translate(glm::mat4(1.0f), glm::vec3(0, 1.2f, 6)));
  p.publish();
  EXPECT_EQ(p.differing(inside), 0u);
  EXPECT_GT(test::differingPixels(before, p.guided.image), 0u) << "the part now stands in the aisle";
  // And moved away again: gone the same frame.
  const med::FrameBuffer inAisle = p.guided.image;
  p.scene.source.find<sg::Transform>(last)->setMatrix(glm::translate(glm::mat4(1.0f), glm::vec3(0, -50, 0)));
  p.publish();
  EXPECT_EQ(p.differing(inside), 0u);
  EXPECT_GT(test::differingPixels(inAisle, p.guided.image), 0u);
}

}  // namespace
