#pragma once
// Every back-end this build has, registered by name.
#include <string>

#include "tsr/med/viewport_registry.hpp"

namespace tsr::app {

void registerBackends(med::ViewportRegistry& registry);
// Every back-end this build has, registered once: for questions about
// their capabilities (a registry is const once filled).
const med::ViewportRegistry& backendRegistry();
// Their names for a help text: "coverage, embree or vulkan".
std::string backendChoices();

}  // namespace tsr::app
