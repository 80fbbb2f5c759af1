#pragma once
// What a wall node does with its screen when the client's swap barrier
// releases a frame: nothing, write files (headless walls, tests), or show
// it in a window (the node program supplies that one: windows are the
// application layer's).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tsr/cluster/messages.hpp"
#include "tsr/med/frame_buffer.hpp"

namespace tsr::cluster {

struct PresentedTile {
  med::PixelRect rect;  // in the client's virtual frame
  med::FrameBuffer image;
};

class Presenter {
 public:
  virtual ~Presenter() = default;
  // On the node's render thread, in frame order. `window`: where the
  // client's config places this screen, if it does.
  virtual void present(std::uint64_t frame, const std::vector<PresentedTile>& tiles,
                       const std::optional<WindowPlacement>& window) = 0;
};

// Each tile as DIR/<node>-frame<N>-<x0>-<y0>.exr, written atomically (a
// reader sees a whole file or none). Errors are logged, never thrown: a full
// disk must not stop the wall.
std::shared_ptr<Presenter> makeFilePresenter(std::string directory, std::string nodeName);

}  // namespace tsr::cluster
