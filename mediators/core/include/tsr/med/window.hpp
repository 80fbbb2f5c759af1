#pragma once
// Ordered layers of viewports over one image, composited by depth and
// alpha. Inactive layers are skipped without cost.
#include <memory>
#include <vector>

#include "tsr/med/viewport.hpp"

namespace tsr::med {

class Window {
 public:
  Viewport& addLayer(std::unique_ptr<Viewport> viewport);
  const std::vector<std::unique_ptr<Viewport>>& layers() const { return layers_; }
  Viewport& layer(std::size_t i) { return *layers_.at(i); }

  // Renders every active layer for `view` and composites them in order.
  FrameBuffer render(const sg::Replica& replica, const View& view, const RenderControl& control = {});
  // The frames the active layers must see ahead of the one shown (the
  // largest Viewport::lookahead()), and prepare() handing one to each.
  std::uint32_t lookahead() const;
  void prepare(const sg::Replica& ahead, std::int64_t frame);
  // Stats of each layer from the last render (inactive layers: default).
  const std::vector<RenderStats>& lastStats() const { return stats_; }

 private:
  std::vector<std::unique_ptr<Viewport>> layers_;
  std::vector<RenderStats> stats_;
};

}  // namespace tsr::med
