#pragma once
// A viewport rendered by the Embree path tracer. Viewports on one replica
// with the same root and background share a context: one device, one
// converted scene. Each viewport keeps its own accumulation buffer, so two
// eyes or two tiles converge independently.
#include <chrono>
#include <memory>
#include <mutex>

#include "denoising.hpp"
#include "embree_scene_adapter.hpp"
#include "pixel_filtering.hpp"
#include "render_outputs.hpp"
#include "tsr/embree/radiance_filter.hpp"
#include "tsr/embree/renderer.hpp"
#include "tsr/med/viewport.hpp"

namespace tsr::med::embree_mediator {

struct EmbreeContext {
  std::shared_ptr<embree::Device> device;
  EmbreeSceneAdapter adapter;
  std::mutex mutex;  // viewports sharing the scene render one at a time
  EmbreeContext(std::shared_ptr<embree::Device> d, sg::ContainerId root, sg::ContainerId background)
      : device(d), adapter(std::move(d), root, background) {}
};

class EmbreeViewport final : public Viewport {
 public:
  EmbreeViewport(ViewportSettings settings, std::shared_ptr<EmbreeContext> context);
  SceneAdapter::Update synchronize(const sg::Replica& replica) override;
  RenderStats render(const sg::Replica& replica, const View& view, FrameBuffer& out,
                     const RenderControl& control) override;
  std::vector<std::string> outputNames() const override;
  std::vector<std::string> resolveInputs() const override;
  std::vector<std::string> resolveOutputs() const override;
  void resolve(FrameBuffer& frame) override;
  const EmbreeContext& context() const { return *context_; }

 private:
  void writeFilterInputs(embree::Scene& scene, const embree::Camera& camera, const embree::Region& traced,
                         const FilterSettings& filter, FrameBuffer& full);
  void renderWhitted(const embree::Camera& camera, const embree::Region& region, FrameBuffer& out,
                     const RenderControl& control, std::chrono::steady_clock::time_point start, RenderStats& stats);
  // traced: whether this render call added samples.
  void resolveLocally(const FilterSettings& filter, std::uint32_t spp, bool traced, FrameBuffer& out,
                      const RenderControl& control);

  std::shared_ptr<EmbreeContext> context_;
  embree::Renderer renderer_;
  std::unique_ptr<embree::FrameBuffer> accumulation_;
  std::unique_ptr<embree::WhittedImage> whitted_;  // mode=whitted: the image shown, apart from the path tracer's
  PixelFilterResolver pixelFilter_;
  DenoiseResolver denoiser_;
  std::unique_ptr<embree::RadianceAccumulator> radiance_;
};

}  // namespace tsr::med::embree_mediator
