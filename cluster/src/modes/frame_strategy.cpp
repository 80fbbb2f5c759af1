#include "modes/frame_strategy.hpp"

#include "tsr/cluster/cluster_window.hpp"
#include "tsr/med/compositing.hpp"

namespace tsr::cluster {

void FrameStrategy::compose(std::vector<med::FrameBuffer>& targets, ClusterFrame& out) const {
  out.image = std::move(targets.at(0));
}

void composeEyes(std::vector<med::FrameBuffer>& targets, StereoCompose compose, ClusterFrame& out) {
  out.left = std::move(targets.at(0));
  out.right = std::move(targets.at(1));
  out.image =
      compose == StereoCompose::Anaglyph ? med::anaglyph(out.left, out.right) : med::sideBySide(out.left, out.right);
}

std::unique_ptr<FrameStrategy> makeFrameStrategy(const ClusterConfig& config) {
  switch (config.mode) {
    case ClusterMode::Cooperative:
      return makeCooperativeStrategy(config.cooperative);
    case ClusterMode::Tiled:
      return makeWallStrategy(config.wall, config.stereo.compose);
    case ClusterMode::Stereo:
      return makeStereoStrategy(config.stereo.compose);
  }
  throw ConfigError("unknown cluster mode");
}

}  // namespace tsr::cluster
