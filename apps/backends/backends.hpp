#pragma once
// Every back-end this build has, registered by name.
#include "tsr/med/viewport_registry.hpp"

namespace tsr::app {

void registerBackends(med::ViewportRegistry& registry);

}  // namespace tsr::app
