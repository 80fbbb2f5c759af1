#include "coverage_viewport.hpp"

#include <chrono>

#include "tsr/med/coverage/false_colour.hpp"
#include "tsr/med/coverage/ranking.hpp"
#include "tsr/med/view_translation.hpp"

namespace tsr::med::coverage_mediator {

CoverageViewport::CoverageViewport(ViewportSettings settings, std::shared_ptr<CoverageContext> context)
    : Viewport(std::move(settings)), context_(std::move(context)) {}

std::vector<std::string> CoverageViewport::outputNames() const { return {kIdOutput}; }

SceneAdapter::Update CoverageViewport::synchronize(const sg::Replica& replica) {
  std::lock_guard lock(context_->mutex);
  return context_->adapter.catchUp(replica);
}

RenderStats CoverageViewport::render(const sg::Replica& replica, const View& view, FrameBuffer& out,
                                     const RenderControl& control) {
  view.validate();
  const auto start = std::chrono::steady_clock::now();
  std::lock_guard lock(context_->mutex);
  RenderStats stats;
  stats.update = context_->adapter.catchUp(replica);
  stats.syncSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const cov::Camera camera = cameraOf(view);
  const cov::Region region = regionOf(view);
  const cov::IdBuffer ids = context_->adapter.scene().renderer().render(camera, region);

  out = FrameBuffer(ids.width(), ids.height());
  out.depth = ids.depth;
  auto& idOut = out.outputs[kIdOutput];
  idOut.resize(ids.ids.size());
  // Neighbouring pixels mostly repeat an id: reuse the last colour.
  cov::ObjectId last = cov::kBackground;
  glm::vec4 colour(0.0f), encoded(0.0f);
  for (std::size_t i = 0; i < ids.ids.size(); ++i) {
    if (ids.ids[i] != last) {
      last = ids.ids[i];
      colour = last == cov::kBackground ? glm::vec4(0.0f) : glm::vec4(falseColour(last), 1.0f);
      encoded = encodeObjectId(last);
    }
    out.colour[i] = colour;
    idOut[i] = encoded;
  }
  stats.rays = ids.ids.size();
  stats.samples = 1;
  if (control.progress) control.progress(1.0);
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace tsr::med::coverage_mediator
