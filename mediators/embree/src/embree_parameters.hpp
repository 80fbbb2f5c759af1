#pragma once
// The path tracer's parameters, declared once (see med::ParameterTable).
#include "tsr/med/viewport_registry.hpp"

namespace tsr::med::embree_mediator {

const BackendCapabilities& embreeCapabilities();
inline const ParameterTable& embreeParameters() { return embreeCapabilities().parameters; }

}  // namespace tsr::med::embree_mediator
