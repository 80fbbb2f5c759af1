#include "backends.hpp"

// registerBackends, one call per back-end the build has (TSR_BACKENDS).
#include "registered_backends.inc"

namespace tsr::app {

const med::ViewportRegistry& backendRegistry() {
  static const med::ViewportRegistry registry = [] {
    med::ViewportRegistry r;
    registerBackends(r);
    return r;
  }();
  return registry;
}

}  // namespace tsr::app
