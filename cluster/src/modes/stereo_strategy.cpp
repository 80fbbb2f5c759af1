// A stereo pair: node 0 renders the left eye, node 1 the right (whoever is
// left when one is gone); the client composes them.
#include <algorithm>

#include "modes/frame_strategy.hpp"

namespace tsr::cluster {

namespace {

class StereoStrategy : public FrameStrategy {
 public:
  explicit StereoStrategy(StereoCompose compose) : compose_(compose) {}

  std::vector<WorkItem> plan(const med::View& view, const Eyes& eyes, const std::vector<std::size_t>& live,
                             std::vector<med::FrameBuffer>& targets) override {
    targets.emplace_back(view.width, view.height);
    targets.emplace_back(view.width, view.height);
    auto pick = [&](std::size_t preferred, std::size_t k) {
      return std::find(live.begin(), live.end(), preferred) != live.end() ? preferred : live[k % live.size()];
    };
    med::View l = view.eye(med::Eye::Left, eyes.separation, eyes.zeroParallax);
    med::View r = view.eye(med::Eye::Right, eyes.separation, eyes.zeroParallax);
    return {{0, l, l.region, 0, ~std::size_t{0}, pick(0, 0)}, {1, r, r.region, 1, ~std::size_t{0}, pick(1, 1)}};
  }

  std::uint32_t viewportsPerNode() const override { return 2; }

  std::map<std::size_t, std::vector<std::size_t>> takeOver(const FrameRound&, std::size_t,
                                                           const std::vector<std::size_t>& pending,
                                                           const std::vector<std::size_t>& live) override {
    std::map<std::size_t, std::vector<std::size_t>> handed;
    if (live.empty()) return handed;
    for (std::size_t k = 0; k < pending.size(); ++k) handed[live[k % live.size()]].push_back(pending[k]);
    return handed;
  }

  void compose(std::vector<med::FrameBuffer>& targets, ClusterFrame& out) const override {
    composeEyes(targets, compose_, out);
  }

 private:
  StereoCompose compose_;
};

}  // namespace

std::unique_ptr<FrameStrategy> makeStereoStrategy(StereoCompose compose) {
  return std::make_unique<StereoStrategy>(compose);
}

}  // namespace tsr::cluster
