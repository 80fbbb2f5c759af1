#include "outputs/stats_json.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "tsr/med/file_replacement.hpp"

namespace tsr::app {

void writeStatsJson(const RenderJob& options, const med::RenderStats& stats, int frames) {
  // Like Embree's own benchmarks, rays per second count the time spent
  // rendering, not the one-off conversion and acceleration-structure build.
  const double renderSeconds = stats.seconds - stats.syncSeconds;
  nlohmann::json j = {{"scene", options.scene},
                      {"backend", options.backend},
                      {"frames", frames},
                      {"seconds", stats.seconds},
                      {"sync_seconds", stats.syncSeconds},
                      {"render_seconds", renderSeconds},
                      {"spp", stats.samples},
                      {"width", options.width},
                      {"height", options.height},
                      {"rays", stats.rays},
                      {"rays_per_second", renderSeconds > 0 ? double(stats.rays) / renderSeconds : 0.0}};
  med::replaceTextFile(options.statsJson, j.dump(2) + "\n");  // never a half-written file
}

void addStats(med::RenderStats& total, const med::RenderStats& more) {
  total.rays += more.rays;
  total.samples = std::max(total.samples, more.samples);
  total.seconds += more.seconds;
  total.syncSeconds += more.syncSeconds;
}

}  // namespace tsr::app
