// The path tracer's photon viewport (temporal = photons) through the real
// back-end: photons run a frame ahead in a second replica while the frame
// shown keeps its own geometry, and misuse is refused.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

#include "../viewport_rig.hpp"
#include "tsr/embree/error.hpp"
#include "tsr/med/embree/register.hpp"

using namespace tsr;

namespace {
constexpr std::uint32_t kSize = 24;

struct PhotonRig : test::ViewportRig {
  PhotonRig() : ViewportRig("embree", med::registerEmbree, "builtin:cornell", kSize) {
    parameters.set("temporal", std::string("photons"));
    parameters.set("photonsPerFrame", std::int64_t{20000});
    parameters.set("photonFrames", std::int64_t{3});
    parameters.set("spp", std::int64_t{2});
    parameters.set("seed", std::int64_t{1});
    parameters.set("maxDepth", std::int64_t{4});
  }
};

// Pixels whose depth differs by more than 5 % (background: both infinite).
std::size_t depthChanges(const med::FrameBuffer& a, const med::FrameBuffer& b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.depth.size(); ++i) {
    const float x = a.depth[i], y = b.depth[i];
    if (std::isinf(x) && std::isinf(y)) continue;
    n += !(std::abs(x - y) <= 0.05f * std::min(x, y));
  }
  return n;
}

// A plain path-traced render of the source as it is now.
med::FrameBuffer pathTraced(const PhotonRig& rig) {
  med::ViewportSettings settings = rig.settings();
  settings.parameters.set("temporal", std::string(""));
  sg::Replica replica;
  replica.apply(rig.source.snapshot());
  med::ContextPool contexts;
  med::FrameBuffer out;
  rig.registry.create(settings, contexts)->render(replica, rig.view(replica.scene()), out);
  return out;
}

TEST(EmbreePhotonViewport, ShowsEachFrameAsPosedWhilePhotonsRunAhead) {
  PhotonRig rig;
  sg::Replica ahead, shown;
  med::ContextPool contexts;
  auto viewport = rig.registry.create(rig.settings(), contexts);
  ASSERT_EQ(viewport->lookahead(), 1u);

  auto list0 = rig.source.commit();
  ahead.apply(list0);
  viewport->prepare(ahead, 0);
  const med::FrameBuffer reference0 = pathTraced(rig);
  auto* box =
      rig.source.find<sg::Transform>(test::findNamed(rig.source, sg::ContainerType::Transform, "mirror sphere"));
  ASSERT_NE(box, nullptr);
  box->setMatrix(glm::translate(box->matrix(), glm::vec3(-100, -250, -250)));
  auto list1 = rig.source.commit();
  ahead.apply(list1);
  viewport->prepare(ahead, 1);
  const med::FrameBuffer reference1 = pathTraced(rig);
  const std::size_t moved = depthChanges(reference0, reference1);
  ASSERT_GT(moved, kSize * kSize / 20) << "the edit must be visible for this test to mean anything";

  med::RenderControl control;
  control.frame = 0;
  med::FrameBuffer frame0, frame1;
  shown.apply(list0);
  const auto stats = viewport->render(shown, rig.view(shown.scene()), frame0, control);
  EXPECT_EQ(stats.samples, 2u);
  EXPECT_LT(depthChanges(frame0, reference0), moved / 4) << "frame 0 shows frame 0's geometry";
  shown.apply(list1);
  control.frame = 1;
  viewport->render(shown, rig.view(shown.scene()), frame1, control);
  EXPECT_LT(depthChanges(frame1, reference1), moved / 4) << "frame 1 shows frame 1's geometry";
  // Photons lit the room: the indirect output carries light.
  double indirect = 0;
  for (const auto& p : frame1.outputs.at("indirect")) indirect += p.r + p.g + p.b;
  EXPECT_GT(indirect, 0.0);
}

TEST(EmbreePhotonViewport, RefusesFramesItCannotShow) {
  PhotonRig rig;
  sg::Replica replica;
  med::ContextPool contexts;
  auto viewport = rig.registry.create(rig.settings(), contexts);
  replica.apply(rig.source.commit());
  med::FrameBuffer out;
  const med::View view = rig.view(replica.scene());
  EXPECT_THROW(viewport->render(replica, view, out), std::invalid_argument);  // no frame
  med::RenderControl control;
  control.frame = 0;
  EXPECT_THROW(viewport->render(replica, view, out, control), embree::Error);  // not prepared
  viewport->prepare(replica, 0);
  EXPECT_NO_THROW(viewport->render(replica, view, out, control));
  rig.parameters.set("photonFrames", std::int64_t{4});  // the window must be centred: odd
  EXPECT_THROW(rig.registry.create(rig.settings(), contexts), med::ParameterError);
}

}  // namespace
