#pragma once
// tessera-render --stats-json: what a render (or a sequence of them) cost.
#include "render_job.hpp"
#include "tsr/med/viewport.hpp"

namespace tsr::app {

// Writes `stats` (summed over `frames` frames) to options.statsJson;
// throws std::runtime_error when the file cannot be written.
void writeStatsJson(const RenderJob& options, const med::RenderStats& stats, int frames);

// Adds one render's statistics to a running total (samples: the most).
void addStats(med::RenderStats& total, const med::RenderStats& more);

}  // namespace tsr::app
