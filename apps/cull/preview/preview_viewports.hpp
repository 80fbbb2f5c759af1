#pragma once
// Where tessera-cull's streamed previews render: here, each stream with a
// viewport of its own over the service's one conversion (streams take
// turns pass by pass), or, with --cluster, on the config's nodes through a
// ClusterViewport (the nodes' back-end; one stream at a time, since the
// cluster's window shows one view).
#include <functional>
#include <memory>
#include <string>

#include "render_job.hpp"
#include "service/cull_service.hpp"
#include "tsr/med/viewport.hpp"

namespace tsr::app {

// Checks the back-end (it must refine progressively) or connects to the
// cluster now, so a mistake stops the service before it listens.
// `job.sequence` holds --cluster, --nodes and the nodes' token file.
std::function<std::unique_ptr<med::Viewport>()> previewViewports(CullService& cull, const std::string& backend,
                                                                 const med::Parameters& parameters,
                                                                 const RenderJob& job, int& maxStreams);

}  // namespace tsr::app
