#pragma once
// Renders a frame sequence of the scene's animation (one frame when no
// --frames was given), locally or through a ClusterWindow, writing one
// image per frame. Returns the process exit status.
#include "render_options.hpp"
#include "sequence_options.hpp"

namespace tsr::app {

int renderSequence(const RenderOptions& options, const SequenceOptions& sequence);

}  // namespace tsr::app
