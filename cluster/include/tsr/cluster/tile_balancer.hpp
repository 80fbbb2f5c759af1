#pragma once
// Sort-first load balancing: which node renders which tile. Starts from
// contiguous runs of tiles, then moves tiles from the busiest node to the
// idlest by measured per-tile cost — only while the imbalance exceeds a
// tolerance and at most a few tiles per frame, because a moved tile loses
// the samples a progressive back-end accumulated for it.
#include <cstdint>
#include <vector>

namespace tsr::cluster {

class TileBalancer {
 public:
  static constexpr std::size_t kNone = ~std::size_t{0};

  TileBalancer(std::size_t tiles, double tolerance, std::uint32_t maxMovesPerFrame);

  // Sets the nodes that can take work. Tiles of nodes no longer present go
  // to the least loaded remaining ones; new nodes start empty and receive
  // tiles through rebalance().
  void setNodes(const std::vector<std::size_t>& nodes);
  // Hands the tiles of a node that died to the others; returns them.
  std::vector<std::size_t> removeNode(std::size_t node);

  // A tile's measured render time (smoothed over frames).
  void record(std::size_t tile, double seconds);
  // Moves tiles for the next frame; returns how many moved.
  std::size_t rebalance();

  std::size_t owner(std::size_t tile) const { return owner_.at(tile); }
  std::vector<std::size_t> tilesOf(std::size_t node) const;
  // Estimated load of a node (sum of its tiles' costs).
  double load(std::size_t node) const;
  // max / mean of the estimated loads of the current nodes.
  double imbalance() const;
  const std::vector<std::size_t>& nodes() const { return nodes_; }

 private:
  std::size_t leastLoaded() const;

  std::vector<std::size_t> owner_;
  std::vector<double> cost_;
  std::vector<std::size_t> nodes_;
  double tolerance_;
  std::uint32_t maxMoves_;
};

}  // namespace tsr::cluster
