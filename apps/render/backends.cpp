#include "backends.hpp"

#include "tsr/med/embree/register.hpp"
#if TSR_HAVE_VULKAN
#include "tsr/med/vulkan/register.hpp"
#endif
#if TSR_HAVE_COVERAGE
#include "tsr/med/coverage/register.hpp"
#endif

namespace tsr::app {

void registerBackends(med::ViewportRegistry& registry) {
  med::registerEmbree(registry);
#if TSR_HAVE_VULKAN
  med::registerVulkan(registry);
#endif
#if TSR_HAVE_COVERAGE
  med::registerCoverage(registry);
#endif
}

}  // namespace tsr::app
