#pragma once
// tessera-render --cluster: the ClusterWindow a config names, with the
// command line's --nodes, --token-file and parameters applied, connected.
#include <memory>
#include <string>
#include <vector>

#include "render_job.hpp"
#include "tsr/cluster/cluster_window.hpp"
#include "tsr/med/viewport_registry.hpp"

namespace tsr::app {

// The --cluster config with --nodes and the command line's parameters
// applied, validated.
cluster::ClusterConfig clusterConfig(const RenderJob& options);
// `outputs`: the named outputs every frame needs. `registry` (for the
// client-side resolve of whole-frame image steps) must outlive the window.
// Throws when no node answers (a wall renders offline tiles instead).
std::unique_ptr<cluster::ClusterWindow> connectCluster(const cluster::ClusterConfig& config, const RenderJob& options,
                                                       std::vector<std::string> outputs,
                                                       const med::ViewportRegistry& registry);

}  // namespace tsr::app
