#include "cluster/cluster_layer.hpp"

#include <algorithm>
#include <stdexcept>

#include "cluster/cluster_connection.hpp"
#include "tsr/cluster/cluster_viewport.hpp"

namespace tsr::app {

RemoteLayers clusterLayer(const RenderJob& options, const std::vector<LayerSpec>& layers,
                          const med::ViewportRegistry& registry, const sg::Camera& camera) {
  const cluster::ClusterConfig config = clusterConfig(options);
  const std::string backend = config.nodes.front().backend;
  const auto uses =
      std::count_if(layers.begin(), layers.end(), [&](const LayerSpec& l) { return l.backend == backend; });
  if (uses == 0)
    throw std::invalid_argument("--cluster: its nodes render with " + backend + ", but no layer of --layers does");
  if (uses > 1)
    throw std::invalid_argument(
        "--cluster: several layers use " + backend +
        ", the nodes' back-end; one cluster renders one layer (give the others another back-end)");
  std::shared_ptr<cluster::ClusterWindow> window = connectCluster(config, options, options.aovs, registry);
  window->setEyes(camera.eyeSeparation(), camera.zeroParallaxDistance());
  // The window goes to the one layer of the nodes' back-end, looking as far
  // ahead as the nodes' viewports of it will (photons: a local one says).
  return [window, outputs = options.aovs, backend,
          registry = &registry](const med::ViewportSettings& settings) -> std::unique_ptr<med::Viewport> {
    if (settings.backend != backend) return nullptr;
    med::ContextPool contexts;
    const std::uint32_t lookahead = registry->create(settings, contexts)->lookahead();
    return std::make_unique<cluster::ClusterViewport>(settings, window, outputs, lookahead);
  };
}

}  // namespace tsr::app
