#pragma once
// tessera-render --layers with --cluster: the one layer of the cluster
// config's back-end renders on the nodes (a cluster::ClusterViewport), the
// others here; the window composites them all alike.
#include <memory>
#include <vector>

#include "layers.hpp"
#include "render_job.hpp"

namespace tsr::app {

// Connects to the --cluster nodes and returns the factory for
// makeLayeredWindow that hands them the layer of their back-end. Throws
// std::invalid_argument, saying why, unless exactly one of `layers` uses
// that back-end (checked before connecting). `camera` gives a stereo
// config its eyes.
RemoteLayers clusterLayer(const RenderJob& options, const std::vector<LayerSpec>& layers,
                          const med::ViewportRegistry& registry, const sg::Camera& camera);

}  // namespace tsr::app
