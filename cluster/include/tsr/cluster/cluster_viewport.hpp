#pragma once
// A cluster as one layer of a med::Window: render() mirrors the replica
// onto the nodes and has them render the view as the config's mode says,
// so a layered window can put, say, the path tracer cooperative on two
// nodes under a rasterised marker layer rendered here. Composited like any
// other layer, by the assembled frame's depth and alpha.
#include <memory>
#include <optional>

#include "tsr/cluster/cluster_window.hpp"
#include "tsr/med/viewport.hpp"

namespace tsr::cluster {

class ClusterViewport : public med::Viewport {
 public:
  // `settings` name the nodes' back-end and what the layer shows (root,
  // background); `outputs` are the ClientOptions outputs `window` was made
  // with, the only named outputs it can fill. `lookahead`: that of the
  // nodes' viewports made with `settings` (the path tracer's photons look
  // ahead); their prepare() runs on the nodes.
  ClusterViewport(med::ViewportSettings settings, std::shared_ptr<ClusterWindow> window,
                  std::vector<std::string> outputs, std::uint32_t lookahead = 0);

  std::uint32_t lookahead() const override { return lookahead_; }
  // Sends the nodes frame `frame` of the scene ahead (ClusterWindow::prepare).
  void prepare(const sg::Replica& ahead, std::int64_t frame) override;

  // Sends the nodes what they miss of the replica: its newest list when
  // they saw the one before, else a snapshot.
  med::SceneAdapter::Update synchronize(const sg::Replica& replica) override;
  // The whole frame is rendered on the nodes; a region of it is cut out.
  med::RenderStats render(const sg::Replica& replica, const med::View& view, med::FrameBuffer& out,
                          const med::RenderControl& control = {}) override;
  std::vector<std::string> outputNames() const override { return outputs_; }

  ClusterWindow& window() { return *window_; }

 private:
  std::shared_ptr<ClusterWindow> window_;
  std::vector<std::string> outputs_;
  std::optional<std::uint64_t> published_;  // replica version the nodes were sent
  std::uint32_t lookahead_ = 0;
  std::optional<std::uint64_t> preparedVersion_;  // of the scene ahead
};

}  // namespace tsr::cluster
