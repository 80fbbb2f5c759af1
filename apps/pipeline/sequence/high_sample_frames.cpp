#include "sequence/high_sample_frames.hpp"

#include <algorithm>
#include <stdexcept>

#include "backends.hpp"
#include "layers.hpp"
#include "tsr/sg/camera.hpp"

namespace tsr::app {

namespace {
constexpr std::uint32_t kTile = 16;
// Seeds of the re-render, apart from those of the frames (seed + frame).
constexpr std::int64_t kSeedOffset = 1 << 20;
}  // namespace

HighSampleFrames::HighSampleFrames(const RenderJob& options, const SceneSession& session)
    : options_(options), session_(session) {
  registerBackends(registry_);
  med::ViewportSettings settings{options.backend, session.imported.root, session.imported.background,
                                 options.parameters, true};
  window_ = makeLayeredWindow({}, session.source, settings, registry_, contexts_);
  for (const auto& layer : window_.layers()) layer->setParameter("spp", std::int64_t{options.temporal.highSpp});
}

void HighSampleFrames::follow(int frame, sg::ChangeListPtr list) {
  if (list) lists_.emplace_back(frame, std::move(list));
}

std::vector<glm::vec4> HighSampleFrames::render(int frame, const std::vector<bool>& need) {
  const auto started = std::chrono::steady_clock::now();
  while (!lists_.empty() && lists_.front().first <= frame) {
    behind_.apply(lists_.front().second);
    lists_.pop_front();
  }
  const std::uint32_t width = options_.width, height = options_.height;
  if (need.size() != std::size_t{width} * height) throw std::logic_error("high samples: a map of the wrong size");
  const auto* camera = behind_.scene().find<sg::Camera>(session_.camera);
  if (!camera) throw std::logic_error("high samples: frame " + std::to_string(frame) + " has no camera");
  const med::View view = med::View::fromCamera(*camera, width, height);
  const med::ParameterTable& table = registry_.capabilities(options_.backend).parameters;
  const std::int64_t seed =
      (table.declares("seed") ? table.integer(options_.parameters, "seed") : 0) + frame + kSeedOffset;
  for (const auto& layer : window_.layers()) layer->setParameter("seed", seed);
  med::RenderControl control;
  control.outputs = std::vector<std::string>{"indirect"};
  std::vector<glm::vec4> out(need.size(), glm::vec4(0.0f));
  for (std::uint32_t ty = 0; ty < height; ty += kTile)
    for (std::uint32_t tx = 0; tx < width; tx += kTile) {
      const med::PixelRect rect{tx, ty, std::min(width, tx + kTile), std::min(height, ty + kTile)};
      bool any = false;
      for (std::uint32_t y = rect.y0; y < rect.y1 && !any; ++y)
        for (std::uint32_t x = rect.x0; x < rect.x1 && !any; ++x) any = need[std::size_t{y} * width + x];
      if (!any) continue;
      med::FrameBuffer tile;
      renderLayered(window_, behind_, view.cropped(rect), tile, control);
      const auto& indirect = tile.outputs.at("indirect");
      for (std::uint32_t y = rect.y0; y < rect.y1; ++y)
        for (std::uint32_t x = rect.x0; x < rect.x1; ++x)
          out[std::size_t{y} * width + x] = indirect[tile.index(x - rect.x0, y - rect.y0)];
      pixels_ += std::size_t{rect.width()} * rect.height();
    }
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

}  // namespace tsr::app
