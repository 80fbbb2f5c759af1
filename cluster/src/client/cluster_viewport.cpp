#include "tsr/cluster/cluster_viewport.hpp"

#include <algorithm>
#include <chrono>

namespace tsr::cluster {

namespace {
// The pixels of `rect` of a whole frame.
med::FrameBuffer cut(const med::FrameBuffer& frame, const med::PixelRect& rect) {
  med::FrameBuffer out(rect.width(), rect.height());
  for (const auto& [name, unused] : frame.outputs) out.outputs[name].resize(out.colour.size());
  for (std::uint32_t y = 0; y < out.height; ++y)
    for (std::uint32_t x = 0; x < out.width; ++x) {
      const std::size_t to = out.index(x, y), from = frame.index(rect.x0 + x, rect.y0 + y);
      out.colour[to] = frame.colour[from];
      out.depth[to] = frame.depth[from];
      for (const auto& [name, pixels] : frame.outputs) out.outputs[name][to] = pixels[from];
    }
  return out;
}
}  // namespace

ClusterViewport::ClusterViewport(med::ViewportSettings settings, std::shared_ptr<ClusterWindow> window,
                                 std::vector<std::string> outputs, std::uint32_t lookahead)
    : med::Viewport(std::move(settings)),
      window_(std::move(window)),
      outputs_(std::move(outputs)),
      lookahead_(lookahead) {
  window_->setContent(settings_.root, settings_.background);
}

namespace {
// The one list that brings a replica from `since` to now, if there is one.
sg::ChangeListPtr deltaSince(const sg::Replica& replica, const std::optional<std::uint64_t>& since) {
  if (!since || *since == replica.version()) return nullptr;
  auto lists = replica.log().since(*since);
  return lists.status == sg::ChangeLog::CatchUp::Deltas && lists.lists.size() == 1 ? lists.lists.front() : nullptr;
}
}  // namespace

void ClusterViewport::prepare(const sg::Replica& ahead, std::int64_t frame) {
  if (lookahead_ == 0) return;
  window_->prepare(ahead.scene(), deltaSince(ahead, preparedVersion_), frame);
  preparedVersion_ = ahead.version();
}

med::SceneAdapter::Update ClusterViewport::synchronize(const sg::Replica& replica) {
  // Published every time, even unchanged: that is when ClusterWindow
  // retries offline nodes (those up to date are skipped).
  const bool changed = published_ != replica.version();
  // ClusterWindow sends a delta only to nodes at its base version; the
  // others (and all of them when no single list bridges the gap) get a snapshot.
  const sg::ChangeListPtr delta = deltaSince(replica, published_);
  window_->publish(replica.scene(), delta);
  published_ = replica.version();
  if (!changed) return med::SceneAdapter::Update::None;
  return delta ? med::SceneAdapter::Update::Synced : med::SceneAdapter::Update::Converted;
}

med::RenderStats ClusterViewport::render(const sg::Replica& replica, const med::View& view, med::FrameBuffer& out,
                                         const med::RenderControl& control) {
  const auto started = std::chrono::steady_clock::now();
  med::RenderStats stats;
  stats.update = synchronize(replica);
  stats.syncSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  med::View whole = view;
  whole.region = {0, 0, view.width, view.height};
  ClusterFrame frame = window_->render(whole, lookahead_ > 0 ? control.frame : -1);
  out = whole.region == view.region ? std::move(frame.image) : cut(frame.image, view.region);
  // The samples the client asked the nodes for; 0 where it left them their default.
  const auto spp = settings_.parameters.all().find("spp");
  const auto* asked = spp == settings_.parameters.all().end() ? nullptr : std::get_if<std::int64_t>(&spp->second);
  stats.samples = asked ? static_cast<std::uint32_t>(std::clamp<std::int64_t>(*asked, 0, 1 << 20)) : 0;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (control.progress) control.progress(1.0);
  return stats;
}

}  // namespace tsr::cluster
