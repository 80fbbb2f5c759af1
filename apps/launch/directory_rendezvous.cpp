#include "directory_rendezvous.hpp"

#include <fstream>
#include <iterator>
#include <thread>

#include "launch_rank.hpp"
#include "rendezvous_text.hpp"
#include "tsr/med/file_replacement.hpp"

namespace tsr::app {

namespace fs = std::filesystem;

namespace {

bool validJobName(const std::string& job) {
  if (job.empty() || job.size() > 128 || job == "." || job == "..") return false;
  for (char c : job)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') return false;
  return true;
}

}  // namespace

DirectoryRendezvous::DirectoryRendezvous(fs::path directory, const std::string& job) {
  if (!validJobName(job))
    throw LaunchError("job name '" + job.substr(0, 64) +
                      "' must be 1 to 128 letters, digits, '.', '_' or '-' (it names the rendezvous folder)");
  directory /= "tessera-" + job;
  folder_ = std::move(directory);
}

fs::path DirectoryRendezvous::rankFile(unsigned rank) const {
  return folder_ / ("rank-" + std::to_string(rank) + ".addr");
}

void DirectoryRendezvous::publish(unsigned rank, const cluster::NodeAddress& address) {
  std::error_code ec;
  fs::create_directories(folder_, ec);
  if (ec) throw LaunchError("cannot create the rendezvous folder " + folder_.string() + ": " + ec.message());
  med::replaceTextFile(rankFile(rank).string(), address.text() + "\n");
}

std::vector<cluster::NodeAddress> DirectoryRendezvous::gather(unsigned size, std::chrono::milliseconds timeout,
                                                              const Progress& progress) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::vector<cluster::NodeAddress> addresses(size > 0 ? size - 1 : 0);
  std::vector<bool> found(addresses.size(), false);
  unsigned published = 0, reported = ~0u;
  while (true) {
    for (unsigned r = 1; r < size; ++r) {
      if (found[r - 1]) continue;
      const fs::path file = rankFile(r);
      std::error_code ec;
      const auto bytes = fs::file_size(file, ec);
      if (ec) continue;  // not there yet
      if (bytes > kMaxRendezvousText)
        throw LaunchError("rendezvous file " + file.string() + " holds " + std::to_string(bytes) +
                          " bytes, not one HOST:PORT line");
      std::ifstream in(file, std::ios::binary);
      const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      addresses[r - 1] = parseAddressFile(text.substr(0, kMaxRendezvousText + 1), file.string());
      found[r - 1] = true;
      ++published;
    }
    if (progress && published != reported) progress(published, size - 1);
    reported = published;
    if (published + 1 == size) return addresses;
    if (std::chrono::steady_clock::now() >= deadline) throw LaunchError(missingRanksMessage(found, where(), timeout));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

void DirectoryRendezvous::markDone() {
  std::error_code ec;
  fs::create_directories(folder_, ec);
  med::replaceTextFile((folder_ / "done").string(), "done\n");
}

bool DirectoryRendezvous::done() {
  std::error_code ec;
  return fs::exists(folder_ / "done", ec);
}

}  // namespace tsr::app

namespace tsr::app {

void DirectoryRendezvous::retire(unsigned rank) {
  std::error_code ec;
  fs::remove(rankFile(rank), ec);
}

void DirectoryRendezvous::cleanUp(unsigned size, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  auto anyLeft = [&] {
    std::error_code ec;
    for (unsigned r = 1; r < size; ++r)
      if (fs::exists(rankFile(r), ec)) return true;
    return false;
  };
  while (anyLeft()) {
    if (std::chrono::steady_clock::now() >= deadline) return;  // a node rank still stopping: leave the folder
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  std::error_code ec;
  fs::remove(folder_ / "done", ec);
  fs::remove(folder_, ec);  // only when empty
}

}  // namespace tsr::app
