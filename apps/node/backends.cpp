#include "backends.hpp"

#ifdef TSR_NODE_HAS_EMBREE
#include "tsr/med/embree/register.hpp"
#endif
#ifdef TSR_NODE_HAS_VULKAN
#include "tsr/med/vulkan/register.hpp"
#endif
#ifdef TSR_NODE_HAS_COVERAGE
#include "tsr/med/coverage/register.hpp"
#endif

namespace tsr::node {

void registerBackends(med::ViewportRegistry& registry) {
#ifdef TSR_NODE_HAS_EMBREE
  med::registerEmbree(registry);
#endif
#ifdef TSR_NODE_HAS_VULKAN
  med::registerVulkan(registry);
#endif
#ifdef TSR_NODE_HAS_COVERAGE
  med::registerCoverage(registry);
#endif
  (void)registry;
}

}  // namespace tsr::node
