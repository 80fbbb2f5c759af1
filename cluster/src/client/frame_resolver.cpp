#include "client/frame_resolver.hpp"

#include <algorithm>

#include "tsr/cluster/workload.hpp"

namespace tsr::cluster {

void FrameResolver::make(const std::vector<ClusterNode>& nodes, const ClientOptions& options, sg::ContainerId root,
                         sg::ContainerId background) {
  if (viewport_ || !options.registry || nodes.empty()) return;
  const NodeConfig& first = nodes.front().config;
  for (const auto& n : nodes)
    if (n.config.backend != first.backend || !(n.config.parameters == first.parameters)) return;
  if (!options.registry->has(first.backend)) return;
  viewport_ = options.registry->create({first.backend, root, background, first.parameters, true}, contexts_);
  inputs_ = viewport_->resolveInputs();
  outputs_ = viewport_->resolveOutputs();
  if (inputs_.empty()) viewport_.reset();
}

void FrameResolver::askOutputs(const ClientOptions& options, std::vector<WorkItem>& items,
                               std::vector<med::FrameBuffer>& targets) const {
  auto has = [](const std::vector<std::string>& v, const std::string& name) {
    return std::find(v.begin(), v.end(), name) != v.end();
  };
  std::vector<std::string> outputs;
  for (const auto& name : options.outputs)
    if ((!viewport_ || !has(outputs_, name)) && name != kWorkloadOutput) outputs.push_back(name);
  for (const auto& name : viewport_ ? inputs_ : std::vector<std::string>{})
    if (!has(outputs, name)) outputs.push_back(name);
  for (auto& it : items) {
    it.outputs = outputs;
    it.resolve = viewport_ == nullptr;
  }
  // Targets hold what nodes send and what the application reads (the
  // resolver fills the latter's remainder), each allocated once.
  std::vector<std::string> held = outputs;
  for (const auto& name : options.outputs)
    if (!has(held, name) && name != kWorkloadOutput) held.push_back(name);
  for (auto& t : targets)
    for (const auto& name : held) t.outputs[name].assign(t.colour.size(), glm::vec4(0.0f));
}

void FrameResolver::resolve(const ClientOptions& options, std::vector<med::FrameBuffer>& targets) {
  if (!viewport_) return;
  for (auto& t : targets) {
    viewport_->resolve(t);
    for (const auto& name : inputs_)
      if (std::find(options.outputs.begin(), options.outputs.end(), name) == options.outputs.end())
        t.outputs.erase(name);
  }
}

}  // namespace tsr::cluster
