// Object-space PCA (temporal = objectPca; Meyer & Anderson 3.1) through the
// real path tracer: the indirect light is denoised on surface elements, so
// a frame does not depend on where the camera was in the other frames, and
// in a static scene the automatic truncation keeps the frames' common light
// and drops their photon noise.
#include <gtest/gtest.h>

#include "../viewport_rig.hpp"
#include "tsr/med/embree/register.hpp"

using namespace tsr;

namespace {
constexpr std::uint32_t kSize = 24;
constexpr int kFrames = 8;  // one window

struct ObjectPcaRig : test::ViewportRig {
  ObjectPcaRig() : ViewportRig("embree", med::registerEmbree, "builtin:cornell", kSize) {
    parameters.set("temporal", std::string("objectPca"));
    parameters.set("photonsPerFrame", std::int64_t{20000});
    parameters.set("pcaWindow", std::int64_t{8});
    parameters.set("pcaOverlap", std::int64_t{2});
    parameters.set("spp", std::int64_t{2});
    parameters.set("seed", std::int64_t{1});
    parameters.set("maxDepth", std::int64_t{4});
    source.commit();  // the import's edits: the sequences start from its snapshot
  }
};

// Renders the static scene's frames 0..kFrames-1, frame f from views[f],
// preparing each frame the viewport's lookahead before it is shown.
std::vector<med::FrameBuffer> renderSequence(const ObjectPcaRig& rig, const std::vector<med::View>& views) {
  sg::Replica replica;
  replica.apply(rig.source.snapshot());
  med::ContextPool contexts;
  auto viewport = rig.registry.create(rig.settings(), contexts);
  EXPECT_EQ(viewport->lookahead(), 7u);  // a window minus one
  std::vector<med::FrameBuffer> frames(kFrames);
  const int lookahead = static_cast<int>(viewport->lookahead());
  for (int posed = 0; posed < kFrames + lookahead; ++posed) {
    if (posed < kFrames) viewport->prepare(replica, posed);
    const int f = posed - lookahead;
    if (f < 0) continue;
    med::RenderControl control;
    control.frame = f;
    control.outputs = std::vector<std::string>{"indirect"};
    viewport->render(replica, views[std::size_t(f)], frames[std::size_t(f)], control);
  }
  return frames;
}

double indirectSum(const med::FrameBuffer& f) {
  double s = 0;
  for (const auto& p : f.outputs.at("indirect")) s += p.r + p.g + p.b;
  return s;
}

TEST(EmbreeObjectPca, AFrameDoesNotDependOnWhereTheCameraWasInOthers) {
  ObjectPcaRig rig;
  const med::View still = rig.view(rig.source);
  med::View moved = still;
  moved.cameraToWorld[3].x += 60.0f;  // the Cornell box is 555 units wide
  const std::vector<med::View> fixed(kFrames, still);
  std::vector<med::View> moving(kFrames, moved);
  moving[3] = still;
  const auto a = renderSequence(rig, fixed), b = renderSequence(rig, moving);
  ASSERT_GT(test::differingPixels(a[2], b[2]), kSize * kSize / 4) << "the camera motion must be visible";
  EXPECT_EQ(test::differingPixels(a[3], b[3]), 0u) << "frame 3, seen from the same place, must be the same";
  EXPECT_EQ(a[3].outputs.at("indirect"), b[3].outputs.at("indirect"));
  EXPECT_GT(indirectSum(a[3]), 0.0) << "photons lit the room";
}

// Mean over pixels and consecutive frames of the squared change of the
// indirect light, relative to its level: the flicker.
double flicker(const std::vector<med::FrameBuffer>& frames) {
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t t = 1; t < frames.size(); ++t) {
    const auto& a = frames[t - 1].outputs.at("indirect");
    const auto& b = frames[t].outputs.at("indirect");
    for (std::size_t p = 0; p < a.size(); ++p) {
      const glm::vec3 d = glm::vec3(b[p]) - glm::vec3(a[p]);
      sum += glm::dot(d, d) / (glm::dot(glm::vec3(a[p]), glm::vec3(a[p])) + 0.01);
      ++n;
    }
  }
  return sum / double(n);
}

TEST(EmbreeObjectPca, AutomaticTruncationRemovesPhotonNoiseInAStaticScene) {
  ObjectPcaRig rig;
  const std::vector<med::View> views(kFrames, rig.view(rig.source));
  rig.parameters.set("pcaModes", std::int64_t{8});  // every mode of a window: each frame's own photons
  const double raw = flicker(renderSequence(rig, views));
  rig.parameters.set("pcaModes", std::int64_t{0});
  const auto denoised = renderSequence(rig, views);
  EXPECT_GT(raw, 0.0);
  EXPECT_LT(flicker(denoised), raw / 10) << "raw flicker " << raw;
  EXPECT_GT(indirectSum(denoised[0]), 0.0);
}

TEST(EmbreeObjectPca, RefusesAWindowItCannotOverlap) {
  ObjectPcaRig rig;
  med::ContextPool contexts;
  rig.parameters.set("pcaOverlap", std::int64_t{8});
  EXPECT_THROW(rig.registry.create(rig.settings(), contexts), med::ParameterError);
  rig.parameters.set("pcaOverlap", std::int64_t{2});
  rig.parameters.set("pcaWindow", std::int64_t{1});
  EXPECT_THROW(rig.registry.create(rig.settings(), contexts), med::ParameterError);
}

}  // namespace
