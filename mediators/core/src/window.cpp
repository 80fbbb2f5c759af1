#include "tsr/med/window.hpp"

#include <algorithm>

#include "tsr/med/compositing.hpp"

namespace tsr::med {

Viewport& Window::addLayer(std::unique_ptr<Viewport> viewport) {
  layers_.push_back(std::move(viewport));
  return *layers_.back();
}

std::uint32_t Window::lookahead() const {
  std::uint32_t frames = 0;
  for (const auto& layer : layers_)
    if (layer->active()) frames = std::max(frames, layer->lookahead());
  return frames;
}

void Window::prepare(const sg::Replica& ahead, std::int64_t frame) {
  for (const auto& layer : layers_)
    if (layer->active()) layer->prepare(ahead, frame);
}

FrameBuffer Window::render(const sg::Replica& replica, const View& view, const RenderControl& control) {
  view.validate();
  stats_.assign(layers_.size(), RenderStats{});
  FrameBuffer result(view.region.width(), view.region.height());
  FrameBuffer layerImage;
  bool first = true;
  for (std::size_t i = 0; i < layers_.size(); ++i) {
    if (!layers_[i]->active()) continue;
    stats_[i] = layers_[i]->render(replica, view, layerImage, control);
    if (first) {
      result = std::move(layerImage);
      layerImage = FrameBuffer{};
      first = false;
    } else {
      compositeByDepth(result, layerImage);
    }
  }
  return result;
}

}  // namespace tsr::med
