#pragma once
// The path tracer's parameters, declared once (see med::ParameterTable).
#include "tsr/embree/render_settings.hpp"
#include "tsr/med/viewport_registry.hpp"

namespace tsr::med::embree_mediator {

const BackendCapabilities& embreeCapabilities();
inline const ParameterTable& embreeParameters() { return embreeCapabilities().parameters; }

// The path tracer's settings of these parameters (embree::describeSettings,
// then what the mediator derives); with seedPerFrame, the seed of
// animation frame `frame` (RenderControl::frame, -1: none).
embree::RenderSettings renderSettingsFrom(const Parameters& parameters, std::int64_t frame = -1);

}  // namespace tsr::med::embree_mediator
