#pragma once
// The local viewport that resolves frames assembled from the nodes' tiles,
// and what it needs. One exists when every node runs the same back-end with
// the same parameters (their frames are then one image) and that back-end
// has whole-frame steps; made once, on the first frame that wants it.

#include <memory>
#include <string>
#include <vector>

#include "client/cluster_node.hpp"
#include "client/frame_round.hpp"
#include "tsr/cluster/cluster_window.hpp"
#include "tsr/med/context_pool.hpp"
#include "tsr/med/frame_buffer.hpp"
#include "tsr/med/viewport.hpp"

namespace tsr::cluster {

class FrameResolver {
 public:
  // Makes the resolver if there is none yet and the nodes allow one.
  void make(const std::vector<ClusterNode>& nodes, const ClientOptions& options, sg::ContainerId root,
            sg::ContainerId background);
  // What each work item asks the nodes for, and the targets allocated for
  // it. Nodes fill what the application reads and the resolver needs; what
  // the resolver makes itself is left out of their work.
  void askOutputs(const ClientOptions& options, std::vector<WorkItem>& items,
                  std::vector<med::FrameBuffer>& targets) const;
  // Resolves each assembled target, then drops the inputs the application
  // did not ask for. Nothing without a resolver.
  void resolve(const ClientOptions& options, std::vector<med::FrameBuffer>& targets);

 private:
  med::ContextPool contexts_;
  std::unique_ptr<med::Viewport> viewport_;
  std::vector<std::string> inputs_;
  std::vector<std::string> outputs_;
};

}  // namespace tsr::cluster
