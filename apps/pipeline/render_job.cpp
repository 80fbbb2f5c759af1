#include "render_job.hpp"

#include <algorithm>

#include "backends.hpp"
#include "tsr/cluster/workload.hpp"

namespace tsr::app {

med::DisplayTransform aovDisplay(const RenderJob& job, const std::string& aov) {
  return aov == cluster::kWorkloadOutput ? med::DisplayTransform{} : job.display;
}

bool asksWorkload(const RenderJob& job) {
  return std::find(job.aovs.begin(), job.aovs.end(), cluster::kWorkloadOutput) != job.aovs.end();
}

std::int64_t samplesPerPixel(const RenderJob& job) {
  const med::ParameterTable& table = backendRegistry().capabilities(job.backend).parameters;
  return table.declares("spp") ? table.integer(job.parameters, "spp") : 1;
}

}  // namespace tsr::app
