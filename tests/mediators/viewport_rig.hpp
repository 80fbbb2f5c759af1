#pragma once
// What every mediator suite needs to drive a back-end through its real
// viewport: a source scene imported from a built-in, a registry holding one
// back-end, a replica that follows the source with a viewport on it, and a
// fresh conversion of the source's current state to compare against.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>

#include "imported_scene.hpp"
#include "tsr/sg/replica.hpp"

namespace tsr::test {

struct ViewportRig : ImportedScene {
  ViewportRig(std::string backendName, void (*registerBackend)(med::ViewportRegistry&), const std::string& scene,
              std::uint32_t imageSize)
      : ImportedScene(std::move(backendName), registerBackend, scene), size(imageSize) {}

  using ImportedScene::view;
  med::View view(const sg::Scene& scene) const { return view(scene, size, size); }

  std::uint32_t size;
};

// A replica that follows the source, with a viewport created on first render.
struct Follower {
  sg::Replica replica;
  med::ContextPool contexts;
  std::unique_ptr<med::Viewport> viewport;
  med::FrameBuffer image;
  med::RenderStats render(const ViewportRig& rig) {
    if (!viewport) viewport = rig.registry.create(rig.settings(), contexts);
    return viewport->render(replica, rig.view(replica.scene()), image);
  }
};

// The source's current state converted from scratch by a brand-new replica and viewport.
inline med::FrameBuffer freshRender(const ViewportRig& rig) {
  Follower f;
  f.replica.apply(rig.source.snapshot());
  EXPECT_EQ(f.render(rig).update, med::SceneAdapter::Update::Converted);
  return f.image;
}

// The first container of `type` whose name contains `name`.
inline sg::ContainerId findNamed(const sg::Scene& scene, sg::ContainerType type, const std::string& name = "") {
  for (auto id : scene.ids())
    if (scene.find(id)->type() == type && (name.empty() || scene.find(id)->name().find(name) != std::string::npos))
      return id;
  return sg::kNoContainer;
}

// Pixels whose colour is not bitwise the same (all of them if the sizes differ).
inline std::size_t differingPixels(const med::FrameBuffer& a, const med::FrameBuffer& b) {
  if (a.colour.size() != b.colour.size()) return std::max(a.colour.size(), b.colour.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.colour.size(); ++i) differ += a.colour[i] != b.colour[i];
  return differ;
}

}  // namespace tsr::test
