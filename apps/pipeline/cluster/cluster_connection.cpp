#include "cluster/cluster_connection.hpp"

#include <algorithm>
#include <iostream>

#include "backends.hpp"
#include "tsr/cluster/auth.hpp"

namespace tsr::app {

cluster::ClusterConfig clusterConfig(const RenderJob& options) {
  const SequenceOptions& sequence = options.sequence;
  cluster::ClusterConfig config = cluster::loadClusterConfig(sequence.cluster);
  if (!sequence.nodes.empty()) config.replaceAddresses(cluster::parseNodeList(sequence.nodes));
  // What the command line names beats the config; the config beats the
  // command line's defaults. A parameter reaches the nodes whose back-end
  // takes it (a mixed config's rasterising node gets no --spp); one that no
  // node's back-end takes is an error.
  const med::ViewportRegistry& registry = backendRegistry();
  std::vector<std::string> backends;
  for (const auto& node : config.nodes)  // a node names what it has when it refuses an unknown back-end
    if (registry.has(node.backend) && std::find(backends.begin(), backends.end(), node.backend) == backends.end())
      backends.push_back(node.backend);
  if (!backends.empty()) registry.requireDeclared(options.parameters, backends);
  for (auto& node : config.nodes) {
    if (!registry.has(node.backend)) continue;
    const med::ParameterTable& table = registry.capabilities(node.backend).parameters;
    for (const auto& [name, value] : options.parameters.all())
      if (table.declares(name) && (options.explicitParameters.count(name) || !node.parameters.has(name))) {
        table.validate(name, value);  // each back-end's range, not only the first's
        node.parameters.set(name, value);
      }
  }
  config.validate();
  for (const auto& node : config.nodes)
    if (options.backendGiven && node.backend != options.backend)
      throw std::invalid_argument("--backend " + options.backend + " with --cluster: the config's nodes render with " +
                                  node.backend + " (set \"backend\" in " + sequence.cluster + ")");
  return config;
}

std::unique_ptr<cluster::ClusterWindow> connectCluster(const cluster::ClusterConfig& config, const RenderJob& options,
                                                       std::vector<std::string> outputs,
                                                       const med::ViewportRegistry& registry) {
  cluster::ClientOptions client;
  if (!options.sequence.tokenFile.empty()) client.token = cluster::readTokenFile(options.sequence.tokenFile);
  // Colour and depth come with every frame; the nodes are asked for the others.
  std::erase_if(outputs, [](const std::string& name) { return med::isColourOutput(name) || med::isDepthOutput(name); });
  client.outputs = std::move(outputs);
  // Whole-frame image steps of the nodes' back-end (pixel filtering) run
  // here on the assembled frame, so tiles show no seams.
  client.registry = &registry;
  auto window = std::make_unique<cluster::ClusterWindow>(config, client);
  std::size_t online = window->connect(config.timeouts.connect);
  if (online == 0 && config.mode != cluster::ClusterMode::Tiled)
    throw std::runtime_error("no cluster node could be reached: " + window->status().front().lastError);
  if (!options.quiet) std::cout << online << " of " << config.nodes.size() << " nodes online\n";
  return window;
}

}  // namespace tsr::app
