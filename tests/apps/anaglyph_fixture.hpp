#pragma once
// What the tessera-anaglyph command tests share: the render settings, the
// two eyes rendered apart and composed here, and image comparisons.
#include <cmath>
#include <cstring>
#include <string>

#include "backends.hpp"
#include "command_runner.hpp"
#include "preview_defaults.hpp"
#include "scene/scene_session.hpp"
#include "tsr/med/compositing.hpp"
#include "tsr/med/image_file.hpp"

namespace tsr::test {

// 64x48 cornell box, few samples; eyes far apart so the two images differ.
inline const std::string kRender = " --size 64x48 --spp 2 --max-depth 3 --seed 7 --threads 1";
inline const float kSeparation = 60, kZeroParallax = 1000;
inline const std::string kEyes = " --eye-separation 60 --zero-parallax 1000";

// Left and right eye rendered by two separate viewports, composed.
inline med::FrameBuffer composedLocally(med::AnaglyphMethod method, float separation = kSeparation) {
  app::SceneSession session;
  session.load("builtin:cornell");
  session.publish();
  med::ViewportRegistry registry;
  app::registerBackends(registry);
  med::ContextPool contexts;
  med::ViewportSettings settings;
  settings.backend = "embree";
  settings.root = session.imported.root;
  settings.background = session.imported.background;
  settings.parameters.set("spp", std::int64_t{2});
  settings.parameters.set("maxDepth", std::int64_t{3});
  settings.parameters.set("seed", std::int64_t{7});
  settings.parameters.set("threads", std::int64_t{1});
  app::usePreviewDefaultsUnlessSet(settings.parameters);  // as tessera-anaglyph opens
  const auto view = med::View::fromCamera(*session.replica.scene().find<sg::Camera>(session.camera), 64, 48);
  med::FrameBuffer left, right;
  registry.create(settings, contexts)
      ->render(session.replica, view.eye(med::Eye::Left, separation, kZeroParallax), left);
  med::ContextPool otherContexts;  // the right eye converts the scene anew: nothing shared with the left
  registry.create(settings, otherContexts)
      ->render(session.replica, view.eye(med::Eye::Right, separation, kZeroParallax), right);
  return med::anaglyph(left, right, method);
}

inline bool sameColour(const med::FrameBuffer& a, const med::FrameBuffer& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.colour.data(), b.colour.data(), a.colour.size() * sizeof(glm::vec4)) == 0;
}

// Largest per-channel difference of two images (same size).
inline float maxDifference(const med::FrameBuffer& a, const med::FrameBuffer& b) {
  float d = 0;
  for (std::size_t i = 0; i < a.colour.size(); ++i)
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(a.colour[i][c] - b.colour[i][c]));
  return d;
}

class AnaglyphCommand : public CommandTest {
 protected:
  Outcome anaglyph(const std::string& args) { return runBinary(TSR_ANAGLYPH_PATH, args); }
  med::FrameBuffer expected(med::AnaglyphMethod method, float separation = kSeparation) {
    // Through the same file writer, so both sides are rounded alike.
    const auto path = (dir / "expected.exr").string();
    med::writeImage(path, composedLocally(method, separation));
    return med::readImage(path);
  }
};

}  // namespace tsr::test
