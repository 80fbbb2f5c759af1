#include "render_job.hpp"

#include "backends.hpp"

namespace tsr::app {

std::int64_t samplesPerPixel(const RenderJob& job) {
  med::ViewportRegistry registry;
  registerBackends(registry);
  const med::ParameterTable& table = registry.capabilities(job.backend).parameters;
  return table.declares("spp") ? table.integer(job.parameters, "spp") : 1;
}

}  // namespace tsr::app
