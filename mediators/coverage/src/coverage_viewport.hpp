#pragma once
// A viewport that shows object ids. Viewports on one replica with the same
// root and thread count share a context: one converted scene.
#include <memory>
#include <mutex>

#include "coverage_scene_adapter.hpp"
#include "tsr/med/viewport.hpp"

namespace tsr::med::coverage_mediator {

struct CoverageContext {
  CoverageSceneAdapter adapter;
  std::mutex mutex;  // viewports sharing the scene render one at a time
  CoverageContext(std::shared_ptr<IdRendererSource> source, sg::ContainerId root)
      : adapter(std::move(source), root, sg::kNoContainer) {}
};

class CoverageViewport final : public Viewport {
 public:
  CoverageViewport(ViewportSettings settings, std::shared_ptr<CoverageContext> context);
  SceneAdapter::Update synchronize(const sg::Replica& replica) override;
  // One ray per pixel centre; `control` gets progress 1 at the end (an id
  // pass is a single step).
  RenderStats render(const sg::Replica& replica, const View& view, FrameBuffer& out,
                     const RenderControl& control) override;
  std::vector<std::string> outputNames() const override;
  const CoverageContext& context() const { return *context_; }

 private:
  std::shared_ptr<CoverageContext> context_;
};

}  // namespace tsr::med::coverage_mediator
