#include "preview/preview_viewports.hpp"

#include <stdexcept>

#include <spdlog/spdlog.h>

#include "cluster/cluster_connection.hpp"
#include "preview_defaults.hpp"
#include "tsr/cluster/cluster_viewport.hpp"

namespace tsr::app {

std::function<std::unique_ptr<med::Viewport>()> previewViewports(CullService& cull, const std::string& backend,
                                                                 const med::Parameters& parameters,
                                                                 const RenderJob& job, int& maxStreams) {
  const med::ViewportRegistry& registry = cull.registry();
  if (!job.sequence.cluster.empty()) {
    RenderJob filtered = job;  // the nodes' own parameters win (clusterConfig)
    filtered.quiet = true;     // stdout's first line is "listening on ..."
    const cluster::ClusterConfig named = cluster::loadClusterConfig(job.sequence.cluster);
    if (!named.nodes.empty() && registry.has(named.nodes.front().backend))
      usePreviewDefaultsUnlessSet(filtered.parameters, &registry.capabilities(named.nodes.front().backend).parameters);
    const cluster::ClusterConfig config = clusterConfig(filtered);
    std::shared_ptr<cluster::ClusterWindow> window = connectCluster(config, filtered, {}, registry);
    spdlog::info("previews render on {} nodes; {}", config.nodes.size(),
                 previewDefaultsLine(config.nodes.front().parameters));
    const med::ViewportSettings settings = cull.settingsFor(config.nodes.front().backend, {});
    if (maxStreams > 1) spdlog::info("previews render on the cluster: one stream at a time");
    maxStreams = 1;
    return [window, settings] {
      return std::make_unique<cluster::ClusterViewport>(settings, window, std::vector<std::string>{});
    };
  }
  if (!registry.has(backend)) throw std::invalid_argument("--preview-backend " + backend + ": no such back-end here");
  if (!registry.capabilities(backend).progressive)
    throw std::invalid_argument("--preview-backend " + backend + ": it does not refine progressively (try embree)");
  med::Parameters filtered = parameters;
  usePreviewDefaultsUnlessSet(filtered, &registry.capabilities(backend).parameters);
  spdlog::info("previews: {}", previewDefaultsLine(filtered));
  const med::ViewportSettings settings = cull.settingsFor(backend, filtered);
  return [&cull, settings] { return cull.registry().create(settings, cull.contexts()); };
}

}  // namespace tsr::app
