// Sort-first rendering: the frame cut into tiles, handed out by a balancer
// that learns from the measured tile times; a lost node's tiles go to the
// nodes the balancer gives them within the same frame.
#include <optional>

#include "modes/frame_strategy.hpp"
#include "tsr/cluster/tile_balancer.hpp"
#include "tsr/cluster/wall_layout.hpp"

namespace tsr::cluster {

namespace {

class CooperativeStrategy : public FrameStrategy {
 public:
  explicit CooperativeStrategy(const CooperativeConfig& config) : config_(config) {}

  std::vector<WorkItem> plan(const med::View& view, const Eyes&, const std::vector<std::size_t>& live,
                             std::vector<med::FrameBuffer>& targets) override {
    if (!balancer_ || width_ != view.width || height_ != view.height) {
      tiles_ = tileGrid(view.width, view.height, config_.tileSize);
      balancer_.emplace(tiles_.size(), config_.tolerance, config_.maxMovesPerFrame);
      width_ = view.width;
      height_ = view.height;
    }
    balancer_->setNodes(live);
    targets.emplace_back(view.width, view.height);
    std::vector<WorkItem> items;
    for (std::size_t t = 0; t < tiles_.size(); ++t) items.push_back({0, view, tiles_[t], 0, t, balancer_->owner(t)});
    return items;
  }

  std::map<std::size_t, std::vector<std::size_t>> takeOver(const FrameRound& round, std::size_t lost,
                                                           const std::vector<std::size_t>& pending,
                                                           const std::vector<std::size_t>& live) override {
    std::map<std::size_t, std::vector<std::size_t>> handed;
    if (live.empty()) return handed;
    balancer_->removeNode(lost);
    for (std::size_t k = 0; k < pending.size(); ++k) {
      const WorkItem& it = round.items()[pending[k]];
      std::size_t to = it.tile != TileBalancer::kNone ? balancer_->owner(it.tile) : live[k % live.size()];
      handed[to].push_back(pending[k]);
    }
    return handed;
  }

  void tileDone(const WorkItem& item, double seconds) override {
    if (item.tile != TileBalancer::kNone) balancer_->record(item.tile, seconds);
  }
  bool frameDone() override {
    balancer_->rebalance();
    return false;
  }
  double imbalance() const override { return balancer_ ? balancer_->imbalance() : 1.0; }

 private:
  CooperativeConfig config_;
  std::optional<TileBalancer> balancer_;
  std::vector<med::PixelRect> tiles_;
  std::uint32_t width_ = 0, height_ = 0;
};

}  // namespace

std::unique_ptr<FrameStrategy> makeCooperativeStrategy(const CooperativeConfig& config) {
  return std::make_unique<CooperativeStrategy>(config);
}

}  // namespace tsr::cluster
