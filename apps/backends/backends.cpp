#include "backends.hpp"

#if TSR_HAVE_EMBREE
#include "tsr/med/embree/register.hpp"
#endif
#if TSR_HAVE_VULKAN
#include "tsr/med/vulkan/register.hpp"
#endif
#if TSR_HAVE_COVERAGE
#include "tsr/med/coverage/register.hpp"
#endif

namespace tsr::app {

void registerBackends(med::ViewportRegistry& registry) {
#if TSR_HAVE_EMBREE
  med::registerEmbree(registry);
#endif
#if TSR_HAVE_VULKAN
  med::registerVulkan(registry);
#endif
#if TSR_HAVE_COVERAGE
  med::registerCoverage(registry);
#endif
  (void)registry;
}

}  // namespace tsr::app
