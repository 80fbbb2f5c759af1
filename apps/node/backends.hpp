#pragma once
// Every back-end this build of the node offers, registered by name.
#include "tsr/med/viewport_registry.hpp"

namespace tsr::node {

void registerBackends(med::ViewportRegistry& registry);

}  // namespace tsr::node
