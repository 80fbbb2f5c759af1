#pragma once
// Rank 0's address on every rank's command line (--rendezvous-address
// HOST:PORT), for clusters without a shared folder: rank 0 listens there,
// each node rank connects, sends one line "rank R HOST:PORT" and keeps the
// connection open; rank 0 closes them all when its client has finished,
// which is the node ranks' word to stop. Addresses are not trusted for
// more than where to connect: with a token, the cluster handshake proves
// each node.
#include <string>
#include <vector>

#include "rendezvous.hpp"
#include "rendezvous_text.hpp"

namespace tsr::app {

class SocketRendezvous final : public Rendezvous {
 public:
  // Rank 0 (`listen`) binds `address` at once, so node ranks may connect
  // whenever they start; node ranks connect in publish(), retrying for up
  // to `connectTimeout` (rank 0 may start later). Throws LaunchError.
  SocketRendezvous(const cluster::NodeAddress& address, bool listen, std::chrono::milliseconds connectTimeout);
  ~SocketRendezvous() override;
  SocketRendezvous(const SocketRendezvous&) = delete;
  SocketRendezvous& operator=(const SocketRendezvous&) = delete;

  std::string where() const override { return "rank 0 at " + address_.text(); }
  void publish(unsigned rank, const cluster::NodeAddress& address) override;
  bool done() override;
  // Lines that are not "rank R HOST:PORT" with R in 1..size-1, seen once,
  // are dropped (and named in the timeout's message).
  std::vector<cluster::NodeAddress> gather(unsigned size, std::chrono::milliseconds timeout,
                                           const Progress& progress = {}) override;
  void markDone() override;

  static constexpr std::size_t kMaxLine = kMaxRendezvousText;

 private:
  cluster::NodeAddress address_;
  std::chrono::milliseconds connectTimeout_;
  int listen_ = -1;         // rank 0
  std::vector<int> nodes_;  // rank 0: connections of the ranks gathered, open until markDone
  int link_ = -1;           // node rank: its connection to rank 0
};

}  // namespace tsr::app
