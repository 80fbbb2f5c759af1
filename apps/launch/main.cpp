// tessera-launch (--rendezvous DIR | --rendezvous-address HOST:PORT) [options] -- CLIENT-COMMAND...
// One command line for every process of a job started by mpirun, srun or
// ssh: rank 0 waits until every other rank has published the address of
// the tessera-node it started, then runs CLIENT-COMMAND with
// `--nodes A,B,...` (rank order) and `--token-file F` appended; when the
// client exits, the nodes are told to stop. docs/launching.md has examples.
// Exit status: the client's on rank 0, 0 on node ranks stopped by rank 0;
// 2 for usage errors, 1 when the rendezvous or a node fails.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <climits>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <thread>

#include "child_process.hpp"
#include "command_line.hpp"
#include "directory_rendezvous.hpp"
#include "error_line.hpp"
#include "launch_rank.hpp"
#include "program_folder.hpp"
#include "socket_rendezvous.hpp"

namespace {

namespace fs = std::filesystem;
using tsr::app::LaunchError;

volatile std::sig_atomic_t stopRequested = 0;
volatile pid_t forwardTo = -1;

void onSignal(int signal) {
  stopRequested = 1;
  if (forwardTo > 0) ::kill(forwardTo, signal);
}

struct LaunchOptions {
  std::string rendezvous, rendezvousAddress, job, tokenFile, nodeBinary, listenHost = "127.0.0.1", advertise;
  std::vector<std::string> nodeArgs, client;
  int rank = -1, size = -1;
  unsigned threads = 0;
  double waitSeconds = 60;
};

// "error: rank R: ..." lines and progress go to stderr: stdout is the client's.
class Console {
 public:
  std::string prefix = "tessera-launch";
  void info(const std::string& text) const { std::cerr << prefix << ": " << text << std::endl; }
};

// tessera-node beside this program (an install or build folder), else on PATH.
std::string defaultNodeBinary() {
  std::error_code ec;
  if (const auto folder = tsr::app::programFolder(); folder && fs::exists(*folder / "tessera-node", ec))
    return (*folder / "tessera-node").string();
  return "tessera-node";
}

std::string advertisedHost(const LaunchOptions& o) {
  if (!o.advertise.empty()) return o.advertise;
  if (o.listenHost != "0.0.0.0" && o.listenHost != "::") return o.listenHost;
  char name[HOST_NAME_MAX + 1] = {};
  if (gethostname(name, sizeof name - 1) != 0) throw LaunchError("cannot read this host's name: give --advertise HOST");
  return name;
}

std::chrono::milliseconds waitLimit(const LaunchOptions& o) {
  return std::chrono::milliseconds(static_cast<long long>(o.waitSeconds * 1000));
}

int runNode(const LaunchOptions& o, const tsr::app::LaunchRank& rank, tsr::app::Rendezvous& meet,
            const Console& console) {
  std::vector<std::string> argv{o.nodeBinary.empty() ? defaultNodeBinary() : o.nodeBinary, "--listen",
                                o.listenHost + ":0", "--name", "rank-" + std::to_string(rank.rank)};
  if (!o.tokenFile.empty()) argv.insert(argv.end(), {"--token-file", o.tokenFile});
  if (o.threads) argv.insert(argv.end(), {"--threads", std::to_string(o.threads)});
  argv.insert(argv.end(), o.nodeArgs.begin(), o.nodeArgs.end());
  tsr::app::ChildProcess node(argv, true);
  forwardTo = node.pid();
  const std::string line = node.readLine(waitLimit(o));
  const std::string prefix = "listening on ";
  if (line.rfind(prefix, 0) != 0) {
    const auto status = node.stop(std::chrono::seconds(2));
    throw LaunchError(argv[0] + " did not report its address within " + std::to_string(o.waitSeconds) +
                      " s (exit status " + std::to_string(status) + ")");
  }
  auto address = tsr::cluster::parseNodeAddress(line.substr(prefix.size()));
  address.host = advertisedHost(o);
  meet.publish(rank.rank, address);
  console.info("node at " + address.text() + " published to " + meet.where());
  while (!stopRequested && !meet.done()) {
    if (auto status = node.poll())
      throw LaunchError("tessera-node exited with status " + std::to_string(*status) + " before the client finished");
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  const int status = node.stop(std::chrono::seconds(5));
  forwardTo = -1;
  meet.retire(rank.rank);
  return stopRequested ? status : 0;
}

int runClient(const LaunchOptions& o, const tsr::app::LaunchRank& rank, tsr::app::Rendezvous& meet,
              const Console& console) {
  struct DoneOnExit {  // the nodes stop however rank 0 leaves
    tsr::app::Rendezvous& meet;
    unsigned size;
    bool gathered = false;  // else the word stays for node ranks that come late
    ~DoneOnExit() {
      try {
        meet.markDone();
        if (gathered) meet.cleanUp(size, std::chrono::seconds(10));
      } catch (...) {}
    }
  } done{meet, rank.size};
  console.info("waiting for " + std::to_string(rank.size - 1) + " node(s) at " + meet.where());
  auto addresses = meet.gather(rank.size, waitLimit(o), [&](unsigned found, unsigned wanted) {
    if (found > 0) console.info(std::to_string(found) + " of " + std::to_string(wanted) + " nodes published");
  });
  done.gathered = true;
  std::string nodes;
  for (const auto& a : addresses) nodes += (nodes.empty() ? "" : ",") + a.text();
  std::vector<std::string> argv = o.client;
  argv.insert(argv.end(), {"--nodes", nodes});
  if (!o.tokenFile.empty()) argv.insert(argv.end(), {"--token-file", o.tokenFile});
  console.info("running " + argv[0] + " with --nodes " + nodes);
  tsr::app::ChildProcess client(argv, false);
  forwardTo = client.pid();
  const int status = client.wait();
  forwardTo = -1;
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Starts a Tessera client (rank 0) and render nodes (other ranks) under mpirun, srun or ssh"};
  LaunchOptions o;
  auto* folder = app.add_option("--rendezvous", o.rendezvous,
                                "folder every host of the job sees; the ranks meet in DIR/tessera-JOB");
  auto* address = app.add_option("--rendezvous-address", o.rendezvousAddress,
                                 "instead of a folder: rank 0 listens on HOST:PORT, the node ranks connect there");
  folder->excludes(address);
  address->excludes(folder);
  app.add_option("--job", o.job, "job name (default: SLURM_JOB_ID.SLURM_STEP_ID or Open MPI's job id); unique per run");
  app.add_option("--rank", o.rank, "this process's rank, when no launcher sets SLURM_PROCID or OMPI_COMM_WORLD_RANK")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--size", o.size, "the job size, with --rank")->check(CLI::PositiveNumber);
  app.add_option("--token-file", o.tokenFile, "shared token: given to every node and appended to the client command")
      ->check(tsr::app::FileName());
  app.add_option("--node-binary", o.nodeBinary, "tessera-node to run on node ranks (default: beside this program)")
      ->check(tsr::app::FileName());
  app.add_option("--listen", o.listenHost, "host the nodes listen on (0.0.0.0: every interface; needs --token-file)");
  app.add_option("--advertise", o.advertise,
                 "host name the nodes publish (default: the --listen host, or this host's name for 0.0.0.0)");
  app.add_option("--threads", o.threads, "render threads per node viewport (0: all cores)");
  app.add_option("--node-arg", o.nodeArgs, "extra argument for tessera-node (repeatable)")->allow_extra_args(false);
  app.add_option("--wait", o.waitSeconds, "seconds to wait for a node to start and for all nodes to publish")
      ->check(tsr::app::FiniteRange(0.1, 3600.0));
  app.add_option("client", o.client, "client command run by rank 0 (after --), e.g. tessera-render SCENE --cluster C");
  app.positionals_at_end();
  Console console;
  tsr::app::LaunchRank rank;
  tsr::cluster::NodeAddress rankZero;
  std::unique_ptr<tsr::app::Rendezvous> meet;
  try {
    app.parse(argc, argv);
    if (o.rendezvous.empty() && o.rendezvousAddress.empty())
      throw LaunchError("give --rendezvous DIR (a shared folder) or --rendezvous-address HOST:PORT (rank 0's)");
    if (!o.rendezvousAddress.empty()) rankZero = tsr::cluster::parseNodeAddress(o.rendezvousAddress);
    // Hosts this rank hands on (to tessera-node, in its published address) are checked here, not by them.
    for (const auto& [option, host] : {std::pair{"--listen", o.listenHost}, std::pair{"--advertise", o.advertise}}) {
      if (host.empty()) continue;
      try {
        tsr::cluster::parseNodeAddress(host + ":0");
      } catch (const std::invalid_argument&) {
        throw LaunchError(std::string(option) + " " + host.substr(0, 64) + ": not a host name or IP address");
      }
    }
    if ((o.rank < 0) != (o.size < 0)) throw LaunchError("--rank and --size go together");
    if (o.rank >= 0) {
      rank = {static_cast<unsigned>(o.rank), static_cast<unsigned>(o.size), o.job, "command line"};
      tsr::app::validateRank(rank);
    } else if (auto fromLauncher = tsr::app::rankFromEnvironment([](const char* name) { return std::getenv(name); })) {
      rank = *fromLauncher;
    } else {
      throw LaunchError("no rank: start under mpirun or srun, or give --rank and --size");
    }
    if (!o.job.empty()) rank.job = o.job;
    if (rank.job.empty() && !o.rendezvous.empty())
      throw LaunchError("no job name from " + rank.source + ": give --job NAME, unique per run");
    if (rank.size < 2) throw LaunchError("a job of 1 process has no node: start at least 2 ranks");
    if (rank.rank == 0 && o.client.empty()) throw LaunchError("no client command: give it after --");
    // What can be checked here is, before any rank waits for the others.
    if (rank.rank == 0)
      tsr::app::checkStartable(o.client.front());
    else
      tsr::app::checkStartable(o.nodeBinary.empty() ? defaultNodeBinary() : o.nodeBinary);
    if (!o.rendezvous.empty()) {
      std::error_code ec;
      if (!fs::is_directory(o.rendezvous, ec))
        throw LaunchError(
            "--rendezvous " + o.rendezvous +
            (fs::exists(o.rendezvous, ec) ? ": not a folder" : ": no such folder (one every host of the job sees)"));
      meet = std::make_unique<tsr::app::DirectoryRendezvous>(o.rendezvous, rank.job);
    } else {
      meet = std::make_unique<tsr::app::SocketRendezvous>(rankZero, rank.rank == 0, waitLimit(o));
    }
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const std::exception& e) {
    tsr::app::printError(e.what());
    return 2;
  }

  console.prefix += " [rank " + std::to_string(rank.rank) + "/" + std::to_string(rank.size) + "]";
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  try {
    return rank.rank == 0 ? runClient(o, rank, *meet, console) : runNode(o, rank, *meet, console);
  } catch (const std::exception& e) {
    std::cerr << "error: rank " << rank.rank << ": " << e.what() << "\n";
    return 1;
  }
}
