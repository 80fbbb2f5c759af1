#pragma once
// Renders a frame sequence of the scene's animation (one frame when no
// --frames was given), locally or through a ClusterWindow, writing one
// image per frame; with `layers`, each frame is a layered window
// (layers.hpp), a layer of it on the cluster with --cluster. Returns the
// process exit status.
#include "layers.hpp"
#include "render_job.hpp"
#include "sequence/sequence_options.hpp"

namespace tsr::app {

int renderSequence(const RenderJob& options, const SequenceOptions& sequence, const std::vector<LayerSpec>& layers);

}  // namespace tsr::app
