#pragma once
// tessera-node --present window: the node's wall tile in a GLFW window,
// placed (position, size, fullscreen) as the client's config says. GLFW
// wants one thread, so the node's main thread runs the window and the
// server runs beside it; the render thread only hands frames over.
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <string>

#include "tsr/cluster/presenter.hpp"

namespace tsr::app {

class WindowPresenter : public cluster::Presenter {
 public:
  explicit WindowPresenter(std::string title) : title_(std::move(title)) {}
  // Render thread: the newest frame replaces one not yet shown.
  void present(std::uint64_t frame, const std::vector<cluster::PresentedTile>& tiles,
               const std::optional<cluster::WindowPlacement>& window) override;
  // Main thread: shows frames until `stop` is set or the window is closed
  // (then returns true). Throws std::runtime_error when no window can open.
  bool run(const std::atomic<bool>& stop);

 private:
  struct Pending {
    std::uint64_t frame = 0;
    med::FrameBuffer image;
    std::optional<cluster::WindowPlacement> placement;
  };
  std::string title_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<Pending> pending_;
};

}  // namespace tsr::app
