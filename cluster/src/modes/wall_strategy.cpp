// A display wall: node i renders screen i's rectangle of the virtual frame
// and presents it when every screen's pixels are in (the swap barrier). A
// lost node's screen shows the offline fill; nobody takes it over, since
// nobody else can show it. On a stereo wall each screen shows one eye; the
// client's frame is then the two stitched eyes, composed.
#include "modes/frame_strategy.hpp"
#include "tsr/cluster/wall_layout.hpp"

namespace tsr::cluster {

namespace {

class WallStrategy : public FrameStrategy {
 public:
  WallStrategy(const WallConfig& wall, StereoCompose compose) : wall_(wall), compose_(compose) {}

  std::vector<WorkItem> plan(const med::View& view, const Eyes& eyes, const std::vector<std::size_t>&,
                             std::vector<med::FrameBuffer>& targets) override {
    auto screens = wallScreens(wall_, view.width, view.height);
    targets.emplace_back(view.width, view.height);
    if (wall_.stereo()) targets.emplace_back(view.width, view.height);
    std::vector<WorkItem> items;
    for (std::size_t t = 0; t < screens.size(); ++t) {
      const auto& eye = screens[t].eye;
      med::View v = eye ? view.eye(*eye, eyes.separation, eyes.zeroParallax) : view;
      std::size_t target = eye == med::Eye::Right ? 1 : 0;
      items.push_back({0, v, screens[t].rect, target, ~std::size_t{0}, t});
    }
    return items;
  }

  bool needsNodes() const override { return false; }

  std::map<std::size_t, std::vector<std::size_t>> takeOver(const FrameRound&, std::size_t,
                                                           const std::vector<std::size_t>&,
                                                           const std::vector<std::size_t>&) override {
    return {};
  }

  bool frameDone() override { return true; }

  void compose(std::vector<med::FrameBuffer>& targets, ClusterFrame& out) const override {
    if (wall_.stereo())
      composeEyes(targets, compose_, out);
    else
      FrameStrategy::compose(targets, out);
  }

 private:
  WallConfig wall_;
  StereoCompose compose_;
};

}  // namespace

std::unique_ptr<FrameStrategy> makeWallStrategy(const WallConfig& wall, StereoCompose compose) {
  return std::make_unique<WallStrategy>(wall, compose);
}

}  // namespace tsr::cluster
