#pragma once
// The bookkeeping of one frame: which rectangle of which viewport each node
// renders, which have arrived, and where their pixels go. Items can move to
// another node mid-frame (a node died) or be given up (a wall tile whose
// node is gone shows the offline fill).
#include <chrono>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tsr/cluster/messages.hpp"
#include "tsr/med/frame_buffer.hpp"

namespace tsr::cluster {

struct WorkItem {
  std::uint32_t viewport = 0;  // on the node
  med::View view;              // the full image
  med::PixelRect rect;
  std::size_t target = 0;              // output buffer
  std::size_t tile = ~std::size_t{0};  // balancer tile, in cooperative mode
  std::size_t node = 0;
  bool done = false;
  bool offline = false;
  std::vector<std::string> outputs = {};  // named outputs asked for with the pixels
  bool resolve = true;                    // false: the client resolves the assembled frame
  // What the node that delivered it reports (RenderTile), once done.
  double seconds = 0;
  double syncSeconds = 0;
  std::uint32_t samples = 0;
  std::uint64_t rays = 0;
};

class FrameRound {
 public:
  // `sequenceFrame`: the animation frame shown (RenderRequest::sequenceFrame).
  FrameRound(std::uint64_t frame, std::vector<WorkItem> items, std::vector<med::FrameBuffer>& targets,
             Compression compression, std::int64_t sequenceFrame = -1);

  std::uint64_t frame() const { return frame_; }
  // The request for the given items (all for one node).
  Frame request(const std::vector<std::size_t>& items) const;
  // Item indices per node, of items not yet done.
  std::map<std::size_t, std::vector<std::size_t>> pendingByNode() const;
  std::vector<std::size_t> pendingOf(std::size_t node) const;

  // Copies a tile's pixels into place; returns the item it completed, or
  // nothing for a stale or unasked-for tile. Throws ProtocolError for pixels
  // that do not decode.
  const WorkItem* onTile(std::size_t node, const RenderTile& tile);
  void onDone(std::size_t node, const FrameDone& done);
  // Requests in flight per node: a frame ends when every FrameDone is in
  // (so busy times are complete), or the node is forgotten (lost).
  void sent(std::size_t node) { ++outstanding_[node]; }
  void forget(std::size_t node) { outstanding_.erase(node); }
  // Nodes the frame still waits for.
  std::vector<std::size_t> awaited() const;
  void reassign(std::size_t item, std::size_t node) { items_.at(item).node = node; }
  // Gives an item up, filling its rectangle with `fill`.
  void giveUp(std::size_t item, const glm::vec4& fill);

  // A node's report that it cannot render this frame: it would fail the
  // same way on every node its work moves to. The first reason counts.
  void fail(const std::string& reason) {
    if (error_.empty()) error_ = reason;
  }
  const std::string& error() const { return error_; }

  bool finished() const;
  bool delivered(std::size_t node) const;  // every item of this node arrived
  const std::vector<WorkItem>& items() const { return items_; }
  const std::map<std::size_t, double>& busySeconds() const { return busy_; }
  const std::map<std::size_t, double>& tileSeconds() const { return tileSeconds_; }
  // The client's own work: decoding and placing tiles.
  double assembleSeconds() const { return assembleSeconds_; }
  // From the first node's FrameDone to the last one's: how long the
  // quickest node waits at the barrier.
  double barrierSeconds() const;

 private:
  std::uint64_t frame_;
  std::vector<WorkItem> items_;
  std::vector<med::FrameBuffer>& targets_;
  Compression compression_;
  std::int64_t sequenceFrame_ = -1;
  std::map<std::size_t, double> busy_;
  std::map<std::size_t, double> tileSeconds_;
  std::map<std::size_t, int> outstanding_;
  std::string error_;
  double assembleSeconds_ = 0;
  std::optional<std::chrono::steady_clock::time_point> firstDone_, lastDone_;
};

}  // namespace tsr::cluster
