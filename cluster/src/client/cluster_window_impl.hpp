#pragma once
// ClusterWindow's state and its named parts: the nodes and their sessions
// (cluster_nodes.cpp), what they send (node_messages.cpp), who is late
// (node_lateness.cpp) and the resolver of assembled frames
// (frame_resolver.hpp). The public calls are in cluster_window.cpp.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "client/cluster_node.hpp"
#include "client/frame_resolver.hpp"
#include "client/frame_round.hpp"
#include "client/link_event.hpp"
#include "modes/frame_strategy.hpp"
#include "tsr/cluster/cluster_window.hpp"

namespace tsr::cluster {

struct ClusterWindow::Impl {
  ClusterConfig config;
  ClientOptions options;
  asio::io_context io;
  asio::executor_work_guard<asio::io_context::executor_type> work{io.get_executor()};
  std::thread thread;
  Inbox inbox;
  std::vector<ClusterNode> nodes;

  std::unique_ptr<FrameStrategy> strategy;
  std::function<void(double)> progress;
  std::size_t reassigned = 0;
  std::uint64_t hashToken = 0;
  std::uint64_t frame = 0;
  bool keepPixels = false;
  Eyes eyes;
  sg::ContainerId root = sg::kNoContainer, background = sg::kNoContainer;
  FrameResolver resolver;
  FrameWorkload lastWorkload;

  Impl(ClusterConfig c, ClientOptions o);
  ~Impl();

  // The nodes and their sessions (cluster_nodes.cpp).
  std::size_t add(NodeConfig c);
  void setState(ClusterNode& n, NodeState state);
  void startConnecting(std::size_t i);
  void retryOffline();
  // Sets a node offline and lets the running frame (if any) give its work away.
  void lose(std::size_t i, const std::string& why, FrameRound* round);
  std::vector<std::size_t> synced() const;
  // The work of a lost node goes where the strategy says, within this
  // frame; what it places nowhere shows the offline fill.
  void takeOver(FrameRound& round, std::size_t lost);
  Frame viewportsFor(const ClusterNode& n) const;
  // The largest change list a message of this kind carries (its limit, less
  // room for its other fields), and the size the config asks a snapshot's
  // parts to have (a container larger than that goes alone in a part, up to
  // the message's bound).
  static std::size_t messageBytes(const MessageSpec& message) { return message.maxPayload - 64; }
  std::size_t snapshotPartBytes(const MessageSpec& message) const {
    return config.snapshotPartBytes ? config.snapshotPartBytes : messageBytes(message);  // splitSnapshot bounds it
  }

  // The steps of one frame (cluster_window.cpp): send the requests (giving
  // up the items of nodes not in sync), wait for the tiles (saying who is
  // late, dropping who misses the deadline), release the barrier, record
  // what each node did.
  void sendRequests(FrameRound& round);
  void awaitFrame(FrameRound& round, std::vector<std::string>& lateNodes);
  void finishFrame(const FrameRound& round, std::uint64_t frameNumber);
  void recordWork(const FrameRound& round, const std::vector<std::size_t>& live, ClusterFrame& result);

  // What the nodes send (node_messages.cpp); `round` is the frame being
  // rendered, null between frames.
  void handle(LinkEvent& e, FrameRound* round);
  // One handler per message a node sends.
  void receive(std::size_t i, const Message& m, FrameRound* round);

  // Who is late (node_lateness.cpp).
  // Where node i stands, and since when; `round` is the running frame (or null).
  std::pair<NodePhase, Clock::time_point> phaseOf(std::size_t i, const FrameRound* round) const;
  // How long node i may stay in one phase of this frame before it is late:
  // judged by what its frames cost, not by one fixed time.
  Clock::duration lateAfter(const ClusterNode& n) const;
  // Says once per frame and phase which awaited node is late, in which phase and since when.
  void reportLate(const FrameRound& round, std::vector<std::string>& late);

  // Handles events until `done` holds or the deadline passes; `round` is
  // the frame they may belong to.
  template <class Done>
  bool pump(Clock::time_point deadline, Done done, FrameRound* round = nullptr) {
    while (!done()) {
      auto e = inbox.pop(deadline);
      if (!e) return done();
      handle(*e, round);
    }
    return true;
  }
  void drain() {
    pump(Clock::now(), [] { return false; });
  }

  bool wantsWorkload() const {
    return std::find(options.outputs.begin(), options.outputs.end(), kWorkloadOutput) != options.outputs.end();
  }
};

}  // namespace tsr::cluster
