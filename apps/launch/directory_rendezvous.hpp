#pragma once
// Where the processes of one job meet: a folder on a directory every host
// of the job sees (NFS, Lustre, or /tmp on one machine). Each node rank
// writes its address to <dir>/tessera-<job>/rank-<R>.addr (atomically, by
// rename); rank 0 waits until every rank's file is there, runs the client,
// then writes "done" so the node ranks stop their nodes and exit.
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "rendezvous.hpp"

namespace tsr::app {

class DirectoryRendezvous final : public Rendezvous {
 public:
  // Throws LaunchError for an empty job name or one with characters other
  // than letters, digits, '.', '_' and '-' (it becomes a folder name).
  DirectoryRendezvous(std::filesystem::path directory, const std::string& job);

  const std::filesystem::path& folder() const { return folder_; }
  std::string where() const override { return folder_.string(); }

  void publish(unsigned rank, const cluster::NodeAddress& address) override;
  bool done() override;
  // Polls the folder; throws at once, naming the file, when one holds no
  // valid HOST:PORT line.
  std::vector<cluster::NodeAddress> gather(unsigned size, std::chrono::milliseconds timeout,
                                           const Progress& progress = {}) override;
  // Writes "done".
  void markDone() override;
  void retire(unsigned rank) override;  // removes the rank's file
  // Removes "done" and the folder once no rank file is left.
  void cleanUp(unsigned size, std::chrono::milliseconds timeout) override;

 private:
  std::filesystem::path rankFile(unsigned rank) const;
  std::filesystem::path folder_;
};

}  // namespace tsr::app
