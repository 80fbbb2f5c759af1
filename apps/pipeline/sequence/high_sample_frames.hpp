#pragma once
// Meyer & Anderson 3.2's importance sampling for image-space --temporal pca:
// a pixel whose truncation map keeps more than m_min modes holds light the
// basis represents poorly, so it is rendered again with
// --temporal-high-spp indirect samples and blended in (temporal::
// blendHighSamples). A window is denoised after all its frames were
// rendered, so this keeps a replica that follows the shown one a window
// behind, posed at the frame being finished, with a window of its own.
#include <chrono>
#include <deque>
#include <memory>
#include <utility>
#include <vector>

#include <glm/vec4.hpp>

#include "render_job.hpp"
#include "scene/scene_session.hpp"
#include "tsr/med/context_pool.hpp"
#include "tsr/med/viewport_registry.hpp"
#include "tsr/med/window.hpp"
#include "tsr/sg/replica.hpp"

namespace tsr::app {

class HighSampleFrames {
 public:
  // The window's layers are those of `options` (the --backend alone).
  HighSampleFrames(const RenderJob& options, const SceneSession& session);

  // The list that brought the shown replica to `frame`; frames in order.
  void follow(int frame, sg::ChangeListPtr list);
  // Frame `frame`'s indirect light at --temporal-high-spp on the 16x16
  // tiles holding a pixel of `need` (one flag per pixel, row by row);
  // zero elsewhere. Frames are asked for in order.
  std::vector<glm::vec4> render(int frame, const std::vector<bool>& need);

  double seconds() const { return seconds_; }
  std::size_t pixelsRendered() const { return pixels_; }

 private:
  const RenderJob& options_;
  const SceneSession& session_;
  med::ViewportRegistry registry_;
  med::ContextPool contexts_;
  med::Window window_;
  sg::Replica behind_;
  std::deque<std::pair<int, sg::ChangeListPtr>> lists_;  // not yet applied to behind_
  double seconds_ = 0;
  std::size_t pixels_ = 0;
};

}  // namespace tsr::app
