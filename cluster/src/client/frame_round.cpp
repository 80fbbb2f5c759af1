#include "client/frame_round.hpp"

#include <algorithm>

#include "tsr/cluster/pixel_codec.hpp"
#include "tsr/cluster/protocol_error.hpp"

namespace tsr::cluster {

FrameRound::FrameRound(std::uint64_t frame, std::vector<WorkItem> items, std::vector<med::FrameBuffer>& targets,
                       Compression compression, std::int64_t sequenceFrame)
    : frame_(frame),
      items_(std::move(items)),
      targets_(targets),
      compression_(compression),
      sequenceFrame_(sequenceFrame) {}

Frame FrameRound::request(const std::vector<std::size_t>& items) const {
  RenderRequest r;
  r.frame = frame_;
  r.compression = compression_;
  r.sequenceFrame = sequenceFrame_;
  for (std::size_t i : items) {
    const WorkItem& it = items_.at(i);
    auto job = std::find_if(r.jobs.begin(), r.jobs.end(), [&](const RenderJob& j) {
      return j.viewport == it.viewport && j.view == it.view && j.outputs == it.outputs && j.resolve == it.resolve;
    });
    if (job == r.jobs.end()) {
      r.jobs.push_back({it.viewport, it.view, {}, it.outputs, it.resolve});
      job = std::prev(r.jobs.end());
    }
    job->rects.push_back(it.rect);
  }
  return makeFrame(r);
}

std::map<std::size_t, std::vector<std::size_t>> FrameRound::pendingByNode() const {
  std::map<std::size_t, std::vector<std::size_t>> out;
  for (std::size_t i = 0; i < items_.size(); ++i)
    if (!items_[i].done && !items_[i].offline) out[items_[i].node].push_back(i);
  return out;
}

std::vector<std::size_t> FrameRound::pendingOf(std::size_t node) const {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < items_.size(); ++i)
    if (!items_[i].done && !items_[i].offline && items_[i].node == node) out.push_back(i);
  return out;
}

const WorkItem* FrameRound::onTile(std::size_t node, const RenderTile& tile) {
  if (tile.frame != frame_) return nullptr;
  for (auto& it : items_) {
    if (it.done || it.offline || it.node != node || it.viewport != tile.viewport || !(it.rect == tile.rect)) continue;
    if (tile.outputs != it.outputs)
      throw ProtocolError(ProtocolError::Kind::Malformed, "RenderTile outputs differ from the ones asked for");
    if ((tile.compression == Compression::Kept) != (compression_ == Compression::Kept))
      throw ProtocolError(ProtocolError::Kind::Malformed, compression_ == Compression::Kept
                                                              ? "RenderTile carries pixels the client left on the node"
                                                              : "RenderTile without the pixels asked for");
    it.seconds = tile.seconds;
    it.syncSeconds = tile.syncSeconds;
    it.samples = tile.samples;
    it.rays = tile.rays;
    if (tile.compression == Compression::Kept) {  // the decoder made sure it carries no bytes
      it.done = true;
      tileSeconds_[node] += tile.seconds;
      return &it;
    }
    auto started = std::chrono::steady_clock::now();
    med::FrameBuffer px =
        decodePixels(tile.rect.width(), tile.rect.height(), tile.compression, tile.pixels, tile.outputs);
    med::FrameBuffer& out = targets_.at(it.target);
    auto place = [&](auto& to, const auto& from) {
      for (std::uint32_t y = 0; y < px.height; ++y)
        std::copy_n(from.begin() + px.index(0, y), px.width, to.begin() + out.index(it.rect.x0, it.rect.y0 + y));
    };
    place(out.colour, px.colour);
    place(out.depth, px.depth);
    for (const auto& name : it.outputs) {
      auto& image = out.outputs[name];
      if (image.empty()) image.assign(out.colour.size(), glm::vec4(0.0f));
      place(image, px.outputs[name]);
    }
    it.done = true;
    tileSeconds_[node] += tile.seconds;
    assembleSeconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return &it;
  }
  return nullptr;
}

void FrameRound::onDone(std::size_t node, const FrameDone& done) {
  if (done.frame != frame_) return;
  busy_[node] += done.busySeconds;
  if (auto it = outstanding_.find(node); it != outstanding_.end() && --it->second <= 0) {
    outstanding_.erase(it);
    lastDone_ = std::chrono::steady_clock::now();
    if (!firstDone_) firstDone_ = lastDone_;
  }
}

double FrameRound::barrierSeconds() const {
  return firstDone_ ? std::chrono::duration<double>(*lastDone_ - *firstDone_).count() : 0.0;
}

void FrameRound::giveUp(std::size_t item, const glm::vec4& fill) {
  WorkItem& it = items_.at(item);
  it.offline = true;
  med::FrameBuffer& out = targets_.at(it.target);
  for (std::uint32_t y = it.rect.y0; y < it.rect.y1; ++y)
    for (std::uint32_t x = it.rect.x0; x < it.rect.x1; ++x) {
      out.colour[out.index(x, y)] = fill;
      out.depth[out.index(x, y)] = med::kNoDepth;
    }
}

std::vector<std::size_t> FrameRound::awaited() const {
  std::vector<std::size_t> out;
  for (const auto& [node, n] : outstanding_) out.push_back(node);
  for (const auto& [node, items] : pendingByNode())
    if (!outstanding_.count(node)) out.push_back(node);
  return out;
}

bool FrameRound::finished() const {
  if (!outstanding_.empty()) return false;
  for (const auto& it : items_)
    if (!it.done && !it.offline) return false;
  return true;
}

bool FrameRound::delivered(std::size_t node) const {
  bool any = false;
  for (const auto& it : items_)
    if (it.node == node) {
      if (!it.done) return false;
      any = true;
    }
  return any;
}

}  // namespace tsr::cluster
