#pragma once
// How the processes of one job learn the nodes' addresses: node ranks
// publish theirs, rank 0 gathers them (bounded, naming the ranks that never
// came) and, when its client has finished, says so; node ranks then stop.
#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "tsr/cluster/node_address.hpp"

namespace tsr::app {

class Rendezvous {
 public:
  using Progress = std::function<void(unsigned published, unsigned wanted)>;
  virtual ~Rendezvous() = default;

  // Where the ranks meet, for messages.
  virtual std::string where() const = 0;

  // Node ranks.
  virtual void publish(unsigned rank, const cluster::NodeAddress& address) = 0;
  // True once rank 0 has said its client finished (or can no longer say so).
  virtual bool done() = 0;
  // This node rank has stopped its node (after done()).
  virtual void retire(unsigned /*rank*/) {}

  // Rank 0: the addresses of ranks 1..size-1 in rank order. Throws
  // LaunchError naming the missing ranks after `timeout`.
  virtual std::vector<cluster::NodeAddress> gather(unsigned size, std::chrono::milliseconds timeout,
                                                   const Progress& progress = {}) = 0;
  virtual void markDone() = 0;
  // After markDone(): waits at most `timeout` for the node ranks to retire
  // and removes what the rendezvous left behind.
  virtual void cleanUp(unsigned /*size*/, std::chrono::milliseconds /*timeout*/) {}
};

// Ranks 3, 4 and 7 -> "ranks 3, 4, 7 published no address in WHERE within 60 s (5 of 8 nodes did)".
std::string missingRanksMessage(const std::vector<bool>& found, const std::string& where,
                                std::chrono::milliseconds timeout);

}  // namespace tsr::app
