#pragma once
// Where the processes of one job meet: a folder on a directory every host
// of the job sees (NFS, Lustre, or /tmp on one machine). Each node rank
// writes its address to <dir>/tessera-<job>/rank-<R>.addr (atomically, by
// rename); rank 0 waits until every rank's file is there, runs the client,
// then writes "done" so the node ranks stop their nodes and exit.
#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "tsr/cluster/node_address.hpp"

namespace tsr::app {

class DirectoryRendezvous {
 public:
  // Throws LaunchError for an empty job name or one with characters other
  // than letters, digits, '.', '_' and '-' (it becomes a folder name).
  DirectoryRendezvous(std::filesystem::path directory, const std::string& job);

  const std::filesystem::path& folder() const { return folder_; }

  void publish(unsigned rank, const cluster::NodeAddress& address) const;
  // The addresses of ranks 1..size-1 in rank order, polled until all are
  // there. Throws LaunchError naming the missing ranks after `timeout`, or
  // the file at once when one holds no valid HOST:PORT line.
  using Progress = std::function<void(unsigned published, unsigned wanted)>;
  std::vector<cluster::NodeAddress> gather(unsigned size, std::chrono::milliseconds timeout,
                                           const Progress& progress = {}) const;

  // Rank 0's word that the client has finished.
  void markDone() const;
  bool done() const;

  // Files larger than this are not address files.
  static constexpr std::uintmax_t kMaxAddressFileBytes = 256;

 private:
  std::filesystem::path rankFile(unsigned rank) const;
  std::filesystem::path folder_;
};

}  // namespace tsr::app
