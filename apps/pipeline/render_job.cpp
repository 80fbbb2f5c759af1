#include "render_job.hpp"

#include "backends.hpp"

namespace tsr::app {

std::int64_t samplesPerPixel(const RenderJob& job) {
  const med::ParameterTable& table = backendRegistry().capabilities(job.backend).parameters;
  return table.declares("spp") ? table.integer(job.parameters, "spp") : 1;
}

}  // namespace tsr::app
