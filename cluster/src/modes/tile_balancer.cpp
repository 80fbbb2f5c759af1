#include "tsr/cluster/tile_balancer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tsr::cluster {

TileBalancer::TileBalancer(std::size_t tiles, double tolerance, std::uint32_t maxMovesPerFrame)
    : owner_(tiles, kNone), cost_(tiles, 1.0), tolerance_(tolerance), maxMoves_(maxMovesPerFrame) {}

void TileBalancer::setNodes(const std::vector<std::size_t>& nodes) {
  bool first = nodes_.empty();
  nodes_ = nodes;
  std::sort(nodes_.begin(), nodes_.end());
  if (nodes_.empty()) {
    std::fill(owner_.begin(), owner_.end(), kNone);
    return;
  }
  if (first) {
    // Contiguous runs: neighbouring tiles on one node share cache and samples.
    for (std::size_t t = 0; t < owner_.size(); ++t) owner_[t] = nodes_[t * nodes_.size() / owner_.size()];
    return;
  }
  for (std::size_t& owner : owner_)
    if (owner == kNone || !std::binary_search(nodes_.begin(), nodes_.end(), owner)) owner = kNone;
  for (std::size_t& owner : owner_)
    if (owner == kNone) owner = leastLoaded();
}

std::vector<std::size_t> TileBalancer::removeNode(std::size_t node) {
  std::vector<std::size_t> moved = tilesOf(node);
  nodes_.erase(std::remove(nodes_.begin(), nodes_.end(), node), nodes_.end());
  for (std::size_t t : moved) owner_[t] = kNone;
  for (std::size_t t : moved)
    if (!nodes_.empty()) owner_[t] = leastLoaded();
  return moved;
}

void TileBalancer::record(std::size_t tile, double seconds) {
  if (!(seconds >= 0) || !std::isfinite(seconds)) return;
  double& c = cost_.at(tile);
  c = 0.5 * c + 0.5 * seconds;
}

std::size_t TileBalancer::rebalance() {
  if (nodes_.size() < 2) return 0;
  // Initial costs are 1 per tile; once measured they are seconds. Normalise
  // nothing: every node of a frame was measured the same way.
  std::size_t moves = 0;
  while (moves < maxMoves_ && imbalance() > 1.0 + tolerance_) {
    std::size_t busy = nodes_.front(), idle = nodes_.front();
    for (std::size_t n : nodes_) {
      if (load(n) > load(busy)) busy = n;
      if (load(n) < load(idle)) idle = n;
    }
    double gap = load(busy) - load(idle);
    // The tile that brings the two closest to even, if any improves the maximum.
    std::size_t best = kNone;
    double bestResidual = gap;
    for (std::size_t t = 0; t < owner_.size(); ++t) {
      if (owner_[t] != busy || !(cost_[t] < gap)) continue;
      double residual = std::abs(gap - 2 * cost_[t]);
      if (residual < bestResidual) {
        bestResidual = residual;
        best = t;
      }
    }
    if (best == kNone) break;
    owner_[best] = idle;
    ++moves;
  }
  return moves;
}

std::vector<std::size_t> TileBalancer::tilesOf(std::size_t node) const {
  std::vector<std::size_t> out;
  for (std::size_t t = 0; t < owner_.size(); ++t)
    if (owner_[t] == node) out.push_back(t);
  return out;
}

double TileBalancer::load(std::size_t node) const {
  double sum = 0;
  for (std::size_t t = 0; t < owner_.size(); ++t)
    if (owner_[t] == node) sum += cost_[t];
  return sum;
}

double TileBalancer::imbalance() const {
  if (nodes_.empty()) return 1.0;
  double max = 0, total = 0;
  for (std::size_t n : nodes_) {
    double l = load(n);
    max = std::max(max, l);
    total += l;
  }
  return total > 0 ? max / (total / static_cast<double>(nodes_.size())) : 1.0;
}

std::size_t TileBalancer::leastLoaded() const {
  std::size_t best = nodes_.front();
  double bestLoad = std::numeric_limits<double>::infinity();
  for (std::size_t n : nodes_) {
    double l = load(n);
    if (l < bestLoad) {
      bestLoad = l;
      best = n;
    }
  }
  return best;
}

}  // namespace tsr::cluster
